// run.json as a record that reproduces a run (src/cli/build_info.*,
// clip_run.cpp, run_command.cpp; docs/outputs.md, "run.json"): the build,
// the machine, the UTC times and the final particle count are recorded, and
// `sphclip run out/x/run.json` re-runs the recorded scene to the same state
// hashes, into another folder than the one it reads.

#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::read_text_csv;
using sph::test::run_sphclip;
using sph::test::TempFolder;

const std::string emitter_scene = std::string(SPHCLIP_SOURCE_DIR) + "/scenes/emitter_fill_2d.json";

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

json read_json(const fs::path& path) {
    return json::parse(read_text(path));
}

std::vector<std::string> column(const fs::path& csv, const std::string& name) {
    const auto table = read_text_csv(csv);
    REQUIRE(table.has(name));
    std::vector<std::string> cells;
    for (std::size_t k = 0; k < table.rows.size(); ++k)
        cells.push_back(table.at(k, name));
    return cells;
}

// The emitter scene for 0.1 s (4 frames) on 2 threads, no pictures: its
// particle count grows from 480.
void run_emitter(const TempFolder& tmp, const fs::path& out) {
    const auto result =
        run_sphclip(tmp, {"run", emitter_scene, "--out", out.string(), "--no-png", "--no-mp4",
                          "--duration", "0.1", "--threads", "2", "--export", "csv", "--quiet"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
}

} // namespace

TEST_CASE("run.json records the build, the machine, UTC times and the final particle count",
          "[cli][run_json]") {
    TempFolder tmp;
    run_emitter(tmp, tmp / "a");
    const json run = read_json(tmp / "a" / "run.json");

    const json& build = run.at("build");
    CHECK(build.at("build_type") == SPHCLIP_BUILD_TYPE);
    const std::string compiler = build.at("compiler");
    CHECK((contains(compiler, "GNU") || contains(compiler, "Clang")));
    CHECK(std::regex_search(compiler, std::regex("[0-9]+\\.[0-9]+")));
    const std::string flags = build.at("flags");
    CHECK(contains(flags, "-fno-math-errno"));
    const std::string arch = build.at("arch");
    if (!arch.empty())
        CHECK(contains(flags, "-march=" + arch));
    CHECK(build.at("instruction_sets").is_array());
#if defined(__x86_64__)
    // Every x86-64 compiler may use SSE2.
    CHECK(build.at("instruction_sets").dump().find("\"sse2\"") != std::string::npos);
#endif
    // Inside a git clone (this source tree is one when .git exists) the
    // commit is known; git describe's form: a hash, maybe a tag before it.
    const std::string commit = build.at("git_commit");
    if (fs::exists(fs::path(SPHCLIP_SOURCE_DIR) / ".git") &&
        std::system("git --version > /dev/null 2>&1") == 0)
        CHECK(std::regex_match(commit, std::regex("([^ ]+-g)?[0-9a-f]{7,40}(-dirty)?")));
    else
        CHECK(commit == "unknown");

    const std::string cpu = run.at("machine").at("cpu_model");
    CHECK(!cpu.empty());
    if (contains(read_text("/proc/cpuinfo"), "model name"))
        CHECK(cpu != "unknown");
    CHECK(run.at("machine").at("logical_cpus").get<int>() >= 1);

    const std::regex utc("[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z");
    const std::string started = run.at("started_utc"), ended = run.at("ended_utc");
    CHECK(std::regex_match(started, utc));
    CHECK(std::regex_match(ended, utc));
    CHECK(started <= ended); // ISO 8601 sorts as text

    CHECK(run.at("threads") == 2);
    // --threads 2: one count, all the steps.
    REQUIRE(run.at("thread_counts").size() == 1);
    CHECK(run.at("thread_counts")[0].at("threads") == 2);
    CHECK(run.at("thread_counts")[0].at("chosen_by") == "--threads");
    CHECK(run.at("thread_counts")[0].at("steps") == run.at("steps"));
    CHECK(run.at("particles") == 480);
    const auto particles = column(tmp / "a" / "stats.csv", "particles");
    CHECK(run.at("final_particles").get<std::size_t>() == std::stoul(particles.back()));
    CHECK(run.at("final_particles").get<std::size_t>() > 480);
    CHECK(run.at("scene_file_absolute") == fs::absolute(emitter_scene).lexically_normal().string());
    CHECK(!run.contains("rerun_of"));
}

TEST_CASE("sphclip run RUN.json re-runs the recorded scene to the same state hashes",
          "[cli][run_json]") {
    TempFolder tmp;
    run_emitter(tmp, tmp / "a");
    const std::string source_text = read_text(tmp / "a" / "run.json");

    // From another folder, by a relative path: the scene's own paths do not
    // depend on where the re-run starts.
    const auto result = run_sphclip(tmp, {"run", "a/run.json", "--out", "b"}, tmp.path());
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(contains(result.output, "re-running a/run.json"));
    CHECK(read_text(tmp / "a" / "run.json") == source_text);

    const auto hashes = column(tmp / "a" / "stats.csv", "state_hash");
    REQUIRE(hashes.size() == 4);
    CHECK(column(tmp / "b" / "stats.csv", "state_hash") == hashes);

    const json source = json::parse(source_text), rerun = read_json(tmp / "b" / "run.json");
    CHECK(rerun.at("scene") == source.at("scene"));
    CHECK(rerun.at("status") == "completed");
    CHECK(rerun.at("final_particles") == source.at("final_particles"));
    // The recorded run options: threads, no pictures, the CSV export.
    CHECK(rerun.at("threads") == 2);
    CHECK(rerun.at("outputs") == source.at("outputs"));
    CHECK(fs::exists(tmp / "b" / "particles" / "frame_00003.csv"));
    CHECK(!fs::exists(tmp / "b" / "frames"));
    const json& from = rerun.at("rerun_of");
    CHECK(from.at("run_json") == (tmp / "a" / "run.json").string());
    CHECK(from.at("started_utc") == source.at("started_utc"));
    CHECK(from.at("git_commit") == source.at("build").at("git_commit"));
    CHECK(rerun.at("scene_file") == "a/run.json");
    CHECK(rerun.at("scene_file_absolute") == source.at("scene_file_absolute"));

    // The command line's options and --set still apply on top.
    const auto shorter = run_sphclip(
        tmp, {"run", "b/run.json", "--out", "c", "--threads", "1", "--duration", "0.05", "--quiet"},
        tmp.path());
    INFO(shorter.output);
    REQUIRE(shorter.exit_code == 0);
    const auto short_hashes = column(tmp / "c" / "stats.csv", "state_hash");
    // 0.05 s at 30 fps: the frames at 0 and 1/30 s as before, then one at 0.05 s.
    REQUIRE(short_hashes.size() == 3);
    CHECK(std::vector<std::string>(short_hashes.begin(), short_hashes.begin() + 2) ==
          std::vector<std::string>(hashes.begin(), hashes.begin() + 2));
    CHECK(column(tmp / "c" / "stats.csv", "time").back() == "0.05");
    CHECK(read_json(tmp / "c" / "run.json").at("threads") == 1);
}

TEST_CASE("A re-run never writes into the folder of the run.json it reads", "[cli][run_json]") {
    TempFolder tmp;
    run_emitter(tmp, tmp / "a");
    const std::string source_text = read_text(tmp / "a" / "run.json");
    const auto before = column(tmp / "a" / "stats.csv", "state_hash");
    const std::vector<std::string> outs{"a", "a/", "./a/.", (tmp / "a").string()};
    for (const std::string& out : outs) {
        const auto result =
            run_sphclip(tmp, {"run", "a/run.json", "--out", out, "--quiet"}, tmp.path());
        INFO(out << ": " << result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "--out"));
        CHECK(contains(result.output, "re-run"));
    }
    CHECK(read_text(tmp / "a" / "run.json") == source_text);
    CHECK(column(tmp / "a" / "stats.csv", "state_hash") == before);
}

TEST_CASE("A re-run without --out goes to the recorded folder's name with -rerun",
          "[cli][run_json]") {
    TempFolder tmp;
    run_emitter(tmp, tmp / "a");
    const auto result = run_sphclip(tmp, {"run", "a/run.json", "--quiet"}, tmp.path());
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(column(tmp / "out" / "emitter_fill_2d-rerun" / "stats.csv", "state_hash") ==
          column(tmp / "a" / "stats.csv", "state_hash"));
}

TEST_CASE("A re-run draws with the recorded GL backend, to the same frames",
          "[cli][run_json][render]") {
    TempFolder tmp;
    const auto first =
        run_sphclip(tmp,
                    {"run", emitter_scene, "--out", "a", "--no-mp4", "--duration", "0.04", "--set",
                     "render.size=[64,48]", "--backend", "osmesa", "--quiet"},
                    tmp.path());
    INFO(first.output);
    REQUIRE(first.exit_code == 0);
    REQUIRE(read_json(tmp / "a" / "run.json").at("gl").at("backend") == "osmesa");

    const auto rerun = run_sphclip(tmp, {"run", "a/run.json", "--out", "b", "--quiet"}, tmp.path());
    INFO(rerun.output);
    REQUIRE(rerun.exit_code == 0);
    CHECK(read_json(tmp / "b" / "run.json").at("gl").at("backend") == "osmesa");
    CHECK(read_text(tmp / "b" / "frames" / "frame_00001.png") ==
          read_text(tmp / "a" / "frames" / "frame_00001.png"));
    CHECK(!fs::exists(tmp / "b" / "clip.mp4"));
}

TEST_CASE("without --threads the run measures its thread count and records each count's steps",
          "[cli][run_json]") {
    TempFolder tmp;
    const auto result = run_sphclip(tmp,
                                    {"run", emitter_scene, "--out", "a", "--no-png", "--no-mp4",
                                     "--duration", "0.1", "--quiet"},
                                    tmp.path());
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    const json run = read_json(tmp / "a" / "run.json");
    const json& counts = run.at("thread_counts");
    REQUIRE(!counts.empty());
    std::uint64_t steps = 0;
    for (const auto& c : counts) {
        const int threads = c.at("threads");
        CHECK(threads >= 1);
        CHECK(threads <= run.at("threads").get<int>());
        // One core: nothing to choose; otherwise measured.
        CHECK(c.at("chosen_by") == (run.at("threads") == 1 ? "all cores" : "measurement"));
        steps += c.at("steps").get<std::uint64_t>();
    }
    CHECK(steps == run.at("steps").get<std::uint64_t>());
    // Its re-run measures again rather than fixing the recorded most.
    const auto rerun_result = run_sphclip(
        tmp, {"run", "a/run.json", "--out", "b", "--duration", "0.05", "--quiet"}, tmp.path());
    INFO(rerun_result.output);
    REQUIRE(rerun_result.exit_code == 0);
    CHECK(read_json(tmp / "b" / "run.json").at("thread_counts")[0].at("chosen_by") ==
          run.at("thread_counts")[0].at("chosen_by"));
}

// cli/wait_policy.hpp, cli/launcher.c: with no policy in the environment, libgomp itself
// reports sphclip's spin count (OMP_DISPLAY_ENV prints what it read at its
// start), so the setting was made before libgomp read it; a policy the user
// sets is kept; run.json records what libgomp read.
TEST_CASE("sphclip sets libgomp's spin count before libgomp reads it, and keeps the user's",
          "[cli][run_json]") {
    TempFolder tmp;
    const auto gomp_report = [&](const std::string& environment,
                                 const std::string& program = SPHCLIP_EXE) {
        const auto log = tmp / "gomp.log";
        const std::string command = fmt::format(
            "env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT {} OMP_DISPLAY_ENV=verbose "
            "{} --version > {} 2>&1",
            environment, sph::test::shell_quote(program), sph::test::shell_quote(log.string()));
        REQUIRE(std::system(command.c_str()) == 0);
        return read_text(log);
    };
    CHECK(contains(gomp_report(""), "GOMP_SPINCOUNT = '10000'"));
    // The program proper named directly starts itself again with it.
    CHECK(contains(gomp_report("", SPHCLIP_PROGRAM), "GOMP_SPINCOUNT = '10000'"));
    CHECK(contains(gomp_report("GOMP_SPINCOUNT=1234"), "GOMP_SPINCOUNT = '1234'"));
    // The user's OMP_WAIT_POLICY alone: libgomp's own spin count for it.
    CHECK_FALSE(contains(gomp_report("OMP_WAIT_POLICY=active"), "GOMP_SPINCOUNT = '10000'"));

    const std::string scene = std::string(SPHCLIP_SOURCE_DIR) + "/scenes/hydrostatic_2d.json";
    const std::string run =
        fmt::format("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT {} run {} --out {} --no-png --no-mp4 "
                    "--duration 0.002 --threads 1 --quiet > {} 2>&1",
                    sph::test::shell_quote(SPHCLIP_EXE), sph::test::shell_quote(scene),
                    sph::test::shell_quote((tmp / "run").string()),
                    sph::test::shell_quote((tmp / "run.log").string()));
    const int status = std::system(run.c_str());
    INFO(read_text(tmp / "run.log"));
    REQUIRE(status == 0);
    const json policy = read_json(tmp / "run" / "run.json").at("wait_policy");
    CHECK(policy.at("GOMP_SPINCOUNT") == "10000");
    CHECK(policy.at("OMP_WAIT_POLICY").is_null());
}
