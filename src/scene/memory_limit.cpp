#include "scene/memory_limit.hpp"

#include <algorithm>
#include <charconv>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace sph {

namespace fs = std::filesystem;

namespace {

// The first word of a small file, or "" when it cannot be read.
std::string first_word(const fs::path& path) {
    std::ifstream in(path);
    std::string word;
    in >> word;
    return word;
}

// A limit file's value; none for "max", for v1's "no limit" (a value near
// 2^63) and for anything unreadable.
std::optional<double> limit_value(const std::string& word) {
    unsigned long long value = 0;
    const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (word.empty() || error != std::errc() || end != word.data() + word.size() ||
        value >= (1ull << 62))
        return std::nullopt;
    return double(value);
}

double gib(double bytes) {
    return bytes / double(1ull << 30);
}

// The tightest `file` from `folder` up to `root`, named in `what`.
std::optional<MemoryLimit> tightest_up_to(const fs::path& root, fs::path folder,
                                          const std::string& file) {
    std::optional<MemoryLimit> best;
    while (true) {
        if (const auto bytes = limit_value(first_word(root / folder / file));
            bytes && (!best || *bytes < best->bytes))
            best = MemoryLimit{*bytes, fmt::format("the cgroup's memory limit ({}) is {:.3g} GiB",
                                                   (root / folder / file).string(), gib(*bytes))};
        if (folder.empty() || folder == folder.parent_path())
            return best;
        folder = folder.parent_path();
    }
}

} // namespace

std::optional<MemoryLimit> cgroup_memory_limit(const std::string& proc_self_cgroup,
                                               const fs::path& cgroup_root) {
    std::istringstream lines(proc_self_cgroup);
    std::optional<MemoryLimit> best;
    const auto take = [&](const std::optional<MemoryLimit>& limit) {
        if (limit && (!best || limit->bytes < best->bytes))
            best = limit;
    };
    for (std::string line; std::getline(lines, line);) {
        // "ID:CONTROLLERS:PATH"; v2 is "0::PATH", v1's memory one "N:memory:PATH".
        const auto first = line.find(':');
        const auto second = first == std::string::npos ? first : line.find(':', first + 1);
        if (second == std::string::npos)
            continue;
        const std::string controllers = line.substr(first + 1, second - first - 1);
        const fs::path path = fs::path(line.substr(second + 1)).relative_path();
        // A container often sees its own cgroup as the mount's root while
        // /proc names the host's path: the path as named, and the root.
        if (controllers.empty()) {
            take(tightest_up_to(cgroup_root, path, "memory.max"));
            take(tightest_up_to(cgroup_root, {}, "memory.max"));
        } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
            take(tightest_up_to(cgroup_root / "memory", path, "memory.limit_in_bytes"));
            take(tightest_up_to(cgroup_root / "memory", {}, "memory.limit_in_bytes"));
        }
    }
    return best;
}

MemoryLimit memory_limit() {
    MemoryLimit best;
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page_size > 0) {
        best.bytes = double(pages) * double(page_size);
        best.what = fmt::format("this machine has {:.3g} GiB", gib(best.bytes));
    }
    const auto take = [&](const MemoryLimit& limit) {
        if (best.bytes <= 0 || limit.bytes < best.bytes)
            best = limit;
    };
    rlimit address_space{};
    if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY) {
        // What the process maps already (libraries, heap) counts against it.
        double mapped = 0;
        if (const auto size = limit_value(first_word("/proc/self/statm")); size && page_size > 0)
            mapped = *size * double(page_size);
        const double limit = double(address_space.rlim_cur);
        take({std::max(0.0, limit - mapped),
              fmt::format("the process's address-space limit (ulimit -v) is {:.3g} GiB, {:.3g} "
                          "GiB of it mapped already",
                          gib(limit), gib(mapped))});
    }
    std::ifstream cgroup_file("/proc/self/cgroup");
    std::stringstream cgroup;
    cgroup << cgroup_file.rdbuf();
    if (const auto limit = cgroup_memory_limit(cgroup.str(), "/sys/fs/cgroup"))
        take(*limit);
    return best;
}

} // namespace sph
