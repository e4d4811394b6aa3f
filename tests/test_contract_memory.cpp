// The memory contract (docs/contract.md, "Memory"): a scene that needs more
// memory than the process may use (the machine's RAM, `ulimit -v`, the
// cgroup's limit, whichever is least) is refused with exit 2 before anything
// is written, naming that limit.

#include "scene/memory_limit.hpp"
#include "support/run_limited.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

#include <catch2/catch.hpp>
#include <fcntl.h>
#include <filesystem>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::test::contains;
using sph::test::read_text;
using sph::test::TempFolder;
using sph::test::write_text;

sph::test::LimitedRun run_with_address_space(const TempFolder& tmp,
                                             const std::vector<std::string>& args,
                                             rlim_t max_bytes) {
    return sph::test::run_with_limit(tmp, args, RLIMIT_AS, max_bytes);
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool address_sanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool address_sanitizer = true;
#else
constexpr bool address_sanitizer = false;
#endif
#else
constexpr bool address_sanitizer = false;
#endif

const std::string square_scene = R"({
    "domain": {"min": [0, 0], "max": [1, 1]},
    "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0], "max": [1, 1]}]},
    "duration": 0.002, "fps": 500
})";

} // namespace

TEST_CASE("memory: a scene beyond ulimit -v is refused with exit 2 before anything is written",
          "[contract][memory]") {
    if (address_sanitizer) {
        WARN("skipped: AddressSanitizer reserves terabytes of address space, so no run "
             "starts under ulimit -v");
        return;
    }
    TempFolder tmp;
    write_text(tmp / "scene.json", square_scene);
    const fs::path out = tmp / "big";
    // 6.25M particles: within this machine's RAM as a rule, far beyond 2 GiB
    // of address space. Unchecked, the run dies of std::bad_alloc (exit 134).
    const auto refused = run_with_address_space(tmp,
                                                {"run", (tmp / "scene.json").string(), "--out",
                                                 out.string(), "--set", "fluid.spacing=0.0004",
                                                 "--no-png", "--no-mp4", "--threads", "1"},
                                                rlim_t(2) << 30);
    INFO(refused.output);
    CHECK(refused.exit_code == 2);
    CHECK(contains(refused.output, "fluid.spacing"));
    CHECK(contains(refused.output, "6.25e+06 particles"));
    CHECK(contains(refused.output, "address-space limit (ulimit -v) is 2 GiB"));
    CHECK(!fs::exists(out));

    // A scene well within the limit still runs under it.
    const auto accepted = run_with_address_space(
        tmp,
        {"run", (tmp / "scene.json").string(), "--out", out.string(), "--set",
         "fluid.spacing=0.004", "--no-png", "--no-mp4", "--threads", "1", "--quiet"},
        rlim_t(2) << 30);
    INFO(accepted.output);
    CHECK(accepted.exit_code == 0);
}

TEST_CASE("memory: the cgroup limit is the tightest memory.max from the cgroup up, v2 and v1",
          "[contract][memory]") {
    TempFolder tmp;
    const fs::path root = tmp / "cgroup";
    // v2: the unit's own limit is "max"; its parent's is 3 GiB, the
    // grandparent's 8 GiB.
    fs::create_directories(root / "user.slice/unit.scope");
    write_text(root / "user.slice/unit.scope/memory.max", "max\n");
    write_text(root / "user.slice/memory.max", "3221225472\n");
    write_text(root / "memory.max", "8589934592\n");
    const auto v2 = sph::cgroup_memory_limit("0::/user.slice/unit.scope\n", root);
    REQUIRE(v2);
    CHECK(v2->bytes == 3221225472.0);
    CHECK(contains(v2->what, "user.slice/memory.max"));
    CHECK(contains(v2->what, "3 GiB"));

    // v1: memory.limit_in_bytes; the "no limit" value (about 2^63) is none.
    fs::create_directories(root / "memory/docker/abc");
    write_text(root / "memory/docker/abc/memory.limit_in_bytes", "1073741824\n");
    write_text(root / "memory/memory.limit_in_bytes", "9223372036854771712\n");
    const auto v1 = sph::cgroup_memory_limit("12:cpu:/\n4:memory:/docker/abc\n", root);
    REQUIRE(v1);
    CHECK(v1->bytes == 1073741824.0);

    // A container that sees its own cgroup as the mount's root while /proc
    // names the host's path: the root's limit is read.
    const fs::path own = tmp / "own";
    fs::create_directories(own / "memory");
    write_text(own / "memory/memory.limit_in_bytes", "536870912\n");
    const auto inside = sph::cgroup_memory_limit("4:memory:/host/path/xyz\n", own);
    REQUIRE(inside);
    CHECK(inside->bytes == 536870912.0);

    // No limit anywhere: none.
    CHECK(!sph::cgroup_memory_limit("0::/\n", tmp / "empty"));
    CHECK(!sph::cgroup_memory_limit("4:memory:/x\n", root / "memory/docker"));
}
