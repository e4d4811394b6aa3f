// Plans (src/cli/plan_*.cpp, collect_command.cpp, slurm_engine.cpp): what
// study, validate and batch write before they run, running and collecting
// them as separate steps, and the Slurm engine's scripts and submission with
// a stand-in sbatch (tests/slurm/check_slurm.sh runs a real Slurm).

#include "support/run_sphclip.hpp"
#include "support/small_tank.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::read_text_csv;
using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::write_text;

// 36 particles, 0.1 s at 40 fps: well under a second a run.
const std::string tiny_scene = sph::test::small_tank(0.1);

json read_json(const fs::path& file) {
    return json::parse(read_text(file));
}

// The last state hash of a run's stats.csv.
std::string last_hash(const fs::path& run) {
    const auto csv = read_text_csv(run / "stats.csv");
    return csv.at(csv.rows.size() - 1, "state_hash");
}

// Sets an environment variable for the scope (the program inherits it).
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& value) : name(std::move(n)) {
        setenv(name.c_str(), value.c_str(), 1);
    }
    ~ScopedEnv() { unsetenv(name.c_str()); }
};

// A stand-in for sbatch: records its arguments, answers a job id.
void write_fake_sbatch(const fs::path& file, const fs::path& calls) {
    write_text(file, "#!/bin/sh\necho \"$@\" >> '" + calls.string() + "'\nn=$(wc -l < '" +
                         calls.string() + "')\necho $((1000 + n))\n");
    fs::permissions(file, fs::perms::owner_all);
}

std::vector<std::string> study_args(const TempFolder& tmp, const fs::path& out) {
    return {"study",    (tmp / "tiny.json").string(),
            "--vary",   "solver.dt=1e-4,2e-4",
            "--vary",   "effects.gravity=[0,-9.81],[0,-1e20]",
            "--metric", "kinetic_energy",
            "--out",    out.string()};
}

} // namespace

TEST_CASE("a study writes its plan, and collect rebuilds its results from the runs",
          "[plan][cli]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    auto args = study_args(tmp, out);
    const auto result = run_sphclip(tmp, args);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);

    const json plan = read_json(out / "plan.json");
    CHECK(plan["kind"] == "study");
    REQUIRE(plan["runs"].size() == 4);
    for (std::size_t i = 0; i < 4; ++i) {
        const fs::path task = out / plan["runs"][i]["task"].get<std::string>();
        const json argv = read_json(task / "command.json");
        CHECK(argv == plan["runs"][i]["argv"]);
        CHECK(argv[1] == "run");
        CHECK(fs::exists(task / "scene.json"));
        // The resolved scene has the run's --set applied.
        CHECK(read_json(task / "scene.json")["solver"]["dt"] == (i < 2 ? 1e-4 : 2e-4));
        CHECK(read_json(task / "exit.json")["exit_code"] == (i % 2 ? 3 : 0));
    }
    // Failed runs are named with their exit codes.
    CHECK_THAT(result.output, Catch::Contains("collect: run 1 (run 01_") &&
                                  Catch::Contains("exit 3 (unstable)") &&
                                  Catch::Contains("collect --resubmit"));

    // Collect alone gives the same table.
    const std::string csv = read_text(out / "study.csv");
    fs::remove(out / "study.csv");
    fs::remove(out / "study.png");
    const auto collected = run_sphclip(tmp, {"collect", out.string()});
    INFO(collected.output);
    CHECK(collected.exit_code == 0);
    CHECK(read_text(out / "study.csv") == csv);
    CHECK(sph::test::is_png(out / "study.png"));

    // A run whose exit record is gone counts as not run.
    fs::remove(out / plan["runs"][2]["task"].get<std::string>() / "exit.json");
    const auto partial = run_sphclip(tmp, {"collect", out.string()});
    CHECK_THAT(partial.output, Catch::Contains("run 2 (run 02_") && Catch::Contains("not run"));
    CHECK(read_text_csv(out / "study.csv").at(2, "status") == "not_run");

    // Sent again with the plan's engine (local): only the runs that did not exit 0.
    const fs::path run0_exit = out / plan["runs"][0]["task"].get<std::string>() / "exit.json";
    const std::string run0_record = read_text(run0_exit);
    const auto again = run_sphclip(tmp, {"collect", "--resubmit", out.string()});
    INFO(again.output);
    CHECK(again.exit_code == 0);
    CHECK_THAT(again.output, Catch::Contains("3 run(s) of"));
    CHECK(read_text(run0_exit) == run0_record);
    CHECK(read_text_csv(out / "study.csv").at(2, "status") == "ok");
}

TEST_CASE("a --dry-run plan runs later with run-plan, or a run at a time with plan-task",
          "[plan][cli]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    auto args = study_args(tmp, out);
    args.push_back("--dry-run");
    const auto planned = run_sphclip(tmp, args);
    INFO(planned.output);
    REQUIRE(planned.exit_code == 0);
    CHECK(fs::exists(out / "plan.json"));
    CHECK_FALSE(fs::exists(out / "study.csv"));
    CHECK_FALSE(fs::exists(out / "plan" / "00" / "exit.json"));

    const auto task = run_sphclip(tmp, {"plan-task", out.string(), "1"});
    CHECK(task.exit_code == 3); // the run's own code: gravity of 1e20 m/s^2 is unstable
    CHECK(read_json(out / "plan" / "01" / "exit.json")["exit_code"] == 3);
    CHECK_FALSE(fs::exists(out / "plan" / "00" / "exit.json"));
    for (const char* bad : {"4", "-1", "x", ""})
        CHECK(run_sphclip(tmp, {"plan-task", out.string(), bad}).exit_code == 2);

    const auto ran = run_sphclip(tmp, {"run-plan", out.string(), "--jobs", "2"});
    INFO(ran.output);
    CHECK(ran.exit_code == 0);
    CHECK(read_text_csv(out / "study.csv").at(0, "status") == "ok");
    CHECK(read_text_csv(out / "study.csv").at(3, "status") == "unstable");

    // A folder without a plan, and a plan copied elsewhere, are refused.
    CHECK(run_sphclip(tmp, {"collect", (tmp / "nowhere").string()}).exit_code == 2);
    fs::create_directories(tmp / "copy");
    fs::copy_file(out / "plan.json", tmp / "copy" / "plan.json");
    const auto copied = run_sphclip(tmp, {"collect", (tmp / "copy").string()});
    CHECK(copied.exit_code == 2);
    CHECK_THAT(copied.output, Catch::Contains("folder"));
}

TEST_CASE("batch runs scenes from the command line and a list; batch.csv has their hashes",
          "[plan][cli]") {
    TempFolder tmp;
    write_text(tmp / "a.json", tiny_scene);
    write_text(tmp / "b.json", tiny_scene);
    write_text(tmp / "list.txt", "# scenes\n" + (tmp / "b.json").string() + "\n\n");
    const fs::path out = tmp / "batch";
    const auto result =
        run_sphclip(tmp, {"batch", (tmp / "a.json").string(), "--list", (tmp / "list.txt").string(),
                          "--no-png", "--no-mp4", "--threads", "1", "--out", out.string()});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    const auto csv = read_text_csv(out / "batch.csv");
    REQUIRE(csv.rows.size() == 2);
    CHECK(csv.at(0, "folder") == "runs/00_a");
    CHECK(csv.at(1, "folder") == "runs/01_b");
    for (std::size_t row = 0; row < 2; ++row) {
        CHECK(csv.at(row, "status") == "ok");
        CHECK(csv.at(row, "exit_code") == "0");
        CHECK(csv.at(row, "state_hash") == last_hash(out / csv.at(row, "folder")));
    }
    // The same scene, the same hash.
    CHECK(csv.at(0, "state_hash") == csv.at(1, "state_hash"));

    SECTION("a missing scene is refused before anything is written") {
        write_text(tmp / "bad.txt", (tmp / "nope.json").string() + "\n");
        const auto r = run_sphclip(
            tmp, {"batch", "--list", (tmp / "bad.txt").string(), "--out", (tmp / "b2").string()});
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains("bad.txt") && Catch::Contains("line 1"));
        CHECK_FALSE(fs::exists(tmp / "b2"));
        CHECK(run_sphclip(tmp, {"batch", "--out", (tmp / "b3").string()}).exit_code == 2);
    }
}

TEST_CASE("the Slurm engine writes one array script and a collect job that waits for it",
          "[plan][cli][slurm]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    auto args = study_args(tmp, out);
    for (const char* a :
         {"--engine", "slurm", "--partition", "short", "--time", "00:10:00", "--cpus-per-task", "2",
          "--max-running", "3", "--sbatch-arg=--account=fluid", "--dry-run"})
        args.push_back(a);
    const auto result = run_sphclip(tmp, args);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    const std::string array = read_text(out / "slurm" / "array.sbatch");
    CHECK_THAT(array, Catch::Contains("#SBATCH --array=0-3%3\n") &&
                          Catch::Contains("#SBATCH --partition=short\n") &&
                          Catch::Contains("#SBATCH --time=00:10:00\n") &&
                          Catch::Contains("#SBATCH --cpus-per-task=2\n") &&
                          Catch::Contains("#SBATCH --account=fluid\n") &&
                          Catch::Contains("plan-task") &&
                          Catch::Contains("\"$SLURM_ARRAY_TASK_ID\""));
    const std::string collect = read_text(out / "slurm" / "collect.sbatch");
    CHECK_THAT(collect, Catch::Contains(" collect ") && Catch::Contains("--partition=short"));
    // --cpus-per-task is each run's --threads.
    CHECK(read_json(out / "plan" / "00" / "command.json").back() == "2");
    CHECK_FALSE(fs::exists(out / "slurm" / "submissions.json"));

    SECTION("submitted: the collect job depends on the array; --resubmit sends only failures") {
        write_fake_sbatch(tmp / "sbatch", tmp / "calls.txt");
        const ScopedEnv sbatch("SPHCLIP_SBATCH", (tmp / "sbatch").string());
        const auto run = run_sphclip(tmp, {"run-plan", out.string()});
        INFO(run.output);
        REQUIRE(run.exit_code == 0);
        const std::string calls = read_text(tmp / "calls.txt");
        CHECK_THAT(calls,
                   Catch::Contains("--parsable " + (out / "slurm" / "array.sbatch").string()) &&
                       Catch::Contains("--dependency=afterany:1001"));
        CHECK(read_json(out / "slurm" / "submissions.json")[0]["array_job"] == "1001");

        // Runs 0 and 2 ended well, 1 was unstable, 3 never ran.
        for (const char* index : {"0", "1", "2"})
            run_sphclip(tmp, {"plan-task", out.string(), index});
        const auto again = run_sphclip(tmp, {"collect", "--resubmit", out.string()});
        INFO(again.output);
        CHECK(again.exit_code == 0);
        CHECK_THAT(again.output, Catch::Contains("exit 3") && Catch::Contains("not run"));
        CHECK_THAT(read_text(out / "slurm" / "array.sbatch"),
                   Catch::Contains("#SBATCH --array=1,3%3\n"));
        CHECK(read_json(out / "slurm" / "submissions.json").size() == 2);
    }
    SECTION("sbatch missing or refusing: exit 5 with a message") {
        {
            const ScopedEnv sbatch("SPHCLIP_SBATCH", (tmp / "no-such-sbatch").string());
            const auto r = run_sphclip(tmp, {"run-plan", out.string()});
            CHECK(r.exit_code == 5);
            CHECK_THAT(r.output, Catch::Contains("no-such-sbatch") && Catch::Contains("sbatch"));
        }
        write_text(tmp / "refuse",
                   "#!/bin/sh\necho 'sbatch: error: invalid partition' >&2\nexit 1\n");
        fs::permissions(tmp / "refuse", fs::perms::owner_all);
        const ScopedEnv sbatch("SPHCLIP_SBATCH", (tmp / "refuse").string());
        const auto r = run_sphclip(tmp, {"run-plan", out.string()});
        CHECK(r.exit_code == 5);
        CHECK_THAT(r.output, Catch::Contains("invalid partition"));
    }
}

TEST_CASE("Slurm options are checked before anything is written", "[plan][cli][slurm]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    const std::vector<std::pair<std::vector<std::string>, std::string>> bad = {
        {{"--engine", "slurm", "--time", "1:2:3:4"}, "--time"},
        {{"--engine", "slurm", "--time", "00:61:00"}, "--time"},
        {{"--engine", "slurm", "--time", "abc"}, "--time"},
        {{"--engine", "slurm", "--partition", "a b"}, "--partition"},
        {{"--engine", "slurm", "--sbatch-arg=account"}, "--sbatch-arg"},
        {{"--engine", "slurm", "--max-running", "0"}, "--max-running"},
        {{"--engine", "pbs"}, "--engine"},
        {{"--partition", "short"}, "--partition"}, // without --engine slurm
        {{"--time", "00:10:00"}, "--time"},
    };
    for (const auto& [flags, named] : bad) {
        auto args = study_args(tmp, out);
        args.insert(args.end(), flags.begin(), flags.end());
        const auto r = run_sphclip(tmp, args);
        INFO(r.output);
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains(named));
        CHECK_FALSE(fs::exists(out));
    }
    // Slurm's other time forms are taken.
    for (const char* time : {"90", "1-00:00:00", "2-12", "10:00"}) {
        auto args = study_args(tmp, out);
        for (const char* a : {"--engine", "slurm", "--dry-run", "--time"})
            args.push_back(a);
        args.push_back(time);
        CHECK(run_sphclip(tmp, args).exit_code == 0);
    }
}

TEST_CASE("validate writes a plan; collect scores it again", "[plan][cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "v";
    const auto result = run_sphclip(tmp,
                                    {"validate", "hydrostatic_2d", "--out", out.string(), "--set",
                                     "fluid.spacing=0.01", "--set", "duration=0.1"},
                                    SPHCLIP_SOURCE_DIR);
    INFO(result.output);
    REQUIRE(fs::exists(out / "summary.csv"));
    CHECK(read_json(out / "plan.json")["kind"] == "validate");
    const std::string summary = read_text(out / "summary.csv");
    fs::remove(out / "summary.csv");
    const auto collected = run_sphclip(tmp, {"collect", out.string()});
    CHECK(collected.exit_code == result.exit_code);
    // The same scores; only the wall time could differ, and it is the run's own.
    CHECK(read_text(out / "summary.csv") == summary);
}

TEST_CASE("under Slurm a scene that does not resolve is refused before the plan is written",
          "[plan][cli][slurm]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    auto args = study_args(tmp, out);
    for (const char* a : {"--set", "fluid.spacingg=0.01", "--engine", "slurm", "--dry-run"})
        args.push_back(a);
    const auto r = run_sphclip(tmp, args);
    CHECK(r.exit_code == 2);
    CHECK_THAT(r.output, Catch::Contains("fluid.spacingg"));
    CHECK_FALSE(fs::exists(out / "plan.json"));
    CHECK_FALSE(fs::exists(out / "slurm"));

    // validate's plan goes to Slurm the same way: one task per case.
    const auto v = run_sphclip(tmp,
                               {"validate", "hydrostatic_2d", "dam_break_2d", "--out",
                                (tmp / "v").string(), "--engine", "slurm", "--dry-run"},
                               SPHCLIP_SOURCE_DIR);
    INFO(v.output);
    CHECK(v.exit_code == 0);
    CHECK_THAT(read_text(tmp / "v" / "slurm" / "array.sbatch"),
               Catch::Contains("#SBATCH --array=0-1\n") &&
                   Catch::Contains("#SBATCH --job-name=sphclip-validate\n"));
}
