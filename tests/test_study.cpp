// `sphclip study`: the plan (--vary, combinations, folder names, the finest
// run), the Pareto front and the frame-series error (src/analysis/), then the
// command end to end on tiny runs.

#include "analysis/frame_series.hpp"
#include "analysis/pareto_front.hpp"
#include "analysis/study_plan.hpp"
#include "scene/input_error.hpp"
#include "support/run_sphclip.hpp"
#include "support/small_tank.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::test::read_text;
using sph::test::read_text_csv;
using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::write_text;

constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

// 6 x 6 = 36 particles in a small box, 0.1 s at 40 fps: a run takes well
// under a second.
const std::string tiny_scene = sph::test::small_tank(0.1);

} // namespace

TEST_CASE("a --vary option is parsed into a key and its values", "[study]") {
    auto v = sph::parse_variation("fluid.spacing=0.004,0.002");
    CHECK(v.key == "fluid.spacing");
    CHECK(v.values == std::vector<std::string>{"0.004", "0.002"});
    CHECK(sph::parse_variation("solver.name=seed").values == std::vector<std::string>{"seed"});
    // Commas inside brackets belong to a value.
    v = sph::parse_variation("fluid.blocks.0.velocity=[1,0],[2,0],{\"a\":[1,2]}");
    CHECK(v.values == std::vector<std::string>{"[1,0]", "[2,0]", "{\"a\":[1,2]}"});

    for (const char* bad : {"fluid.spacing", "=1,2", "fluid.spacing=", "fluid.spacing=1,,2",
                            "fluid.spacing=1,", "v=[1,0", "v=1,1"})
        CHECK_THROWS_AS(sph::parse_variation(bad), sph::InputError);
}

TEST_CASE("combinations are the cartesian product, the last --vary fastest", "[study]") {
    const auto all = sph::expand_combinations(
        {{"solver.name", {"seed", "wcsph"}}, {"fluid.spacing", {"1", "2", "3"}}});
    REQUIRE(all.size() == 6);
    CHECK(all[0] == sph::Combination{{"solver.name", "seed"}, {"fluid.spacing", "1"}});
    CHECK(all[2] == sph::Combination{{"solver.name", "seed"}, {"fluid.spacing", "3"}});
    CHECK(all[3] == sph::Combination{{"solver.name", "wcsph"}, {"fluid.spacing", "1"}});
    CHECK(sph::expand_combinations({}).size() == 1); // one run with nothing varied
    CHECK_THROWS_AS(sph::expand_combinations({{"a", {"1"}}, {"a", {"2"}}}), sph::InputError);
}

TEST_CASE("run folders are numbered in order and safe to name", "[study]") {
    CHECK(sph::run_folder_name(3, 8, {{"fluid.spacing", "0.004"}}) == "03_fluid.spacing=0.004");
    CHECK(sph::run_folder_name(7, 120, {{"a", "1"}, {"b", "x"}}) == "007_a=1_b=x");
    CHECK(sph::run_folder_name(0, 2, {{"v", "[1,0]"}, {"p", "a/b c"}}) == "00_v=_1_0__p=a_b_c");
}

TEST_CASE("the finest run has the most particles, then the smallest time step", "[study]") {
    CHECK(sph::finest_run({{true, 100, 1e-4}, {true, 400, 2e-4}, {true, 400, 1e-4}}) == 2u);
    CHECK(sph::finest_run({{true, 100, 1e-4}, {false, 400, 1e-4}}) == 0u);
    CHECK(sph::finest_run({{true, 100, 1e-4}, {true, 100, 1e-4}}) == 0u);
    CHECK_FALSE(sph::finest_run({{false, 100, 1e-4}}).has_value());
    CHECK_FALSE(sph::finest_run({}).has_value());
}

TEST_CASE("the Pareto front: no other run is cheaper and more accurate", "[study]") {
    //              0: front   1: front  2: dominated by 1  3: front  4: invalid  5: equal to 1
    const auto optimal =
        sph::pareto_optimal({{1, 10}, {2, 5}, {3, 6}, {10, 1}, {not_a_number, 0.1}, {2, 5}});
    CHECK(optimal == std::vector<bool>{true, true, false, true, false, true});
    CHECK(sph::pareto_optimal({{1, 1}, {1, 2}}) == std::vector<bool>{true, false});
    CHECK(sph::pareto_optimal({}).empty());
}

TEST_CASE("frame series are compared with the reference's, interpolated in time", "[study]") {
    const sph::FrameSeries reference{{0, 1, 2}, {{0, 0}, {1, 0}, {2, 0}}};
    CHECK(sph::rms_difference(reference, reference, 1) == 0);
    // Offset by (0, 0.5) everywhere, at times between the reference's frames.
    const sph::FrameSeries shifted{{0.5, 1.5}, {{0.5, 0.5}, {1.5, 0.5}}};
    CHECK(sph::rms_difference(shifted, reference, 1) == Approx(0.5));
    CHECK(sph::rms_difference(shifted, reference, 10) == Approx(0.05));
    // Errors 3 and 4 at two frames: RMS = sqrt((9 + 16) / 2).
    const sph::FrameSeries off{{0, 2}, {{3, 0}, {2, 4}}};
    CHECK(sph::rms_difference(off, reference, 1) == Approx(std::sqrt(12.5)));
    // Frames outside the reference's time are left out.
    CHECK(std::isnan(sph::rms_difference({{5}, {{0, 0}}}, reference, 1)));
}

TEST_CASE("centre of mass and surface height of a particle frame", "[study]") {
    sph::ParticleFrame f;
    f.dimension = 2;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 2; ++j) {
            f.position.insert(f.position.end(), {0.5 + i, 0.5 + j});
            f.velocity.insert(f.velocity.end(), {0.0, 0.0});
            f.density.push_back(1000);
            f.pressure.push_back(0);
        }
    CHECK(sph::centre_of_mass(f) == std::vector<double>{2, 1});
    CHECK(sph::surface_height(f, 1) == Approx(2));
    // A droplet high above does not count.
    f.position.insert(f.position.end(), {0.5, 9});
    f.velocity.insert(f.velocity.end(), {0.0, 0.0});
    f.density.push_back(1000);
    f.pressure.push_back(0);
    CHECK(sph::surface_height(f, 1) == Approx(2));
}

TEST_CASE("a study of a coarse dam break writes study.csv, study.md and study.png",
          "[study][cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "study";
    const auto result = run_sphclip(
        tmp,
        {"study", "scenes/dam_break_2d.json", "--set", "fluid.spacing=0.004", "--duration", "0.1",
         "--vary", "fluid.spacing=0.004,0.006", "--jobs", "2", "--out", out.string()},
        SPHCLIP_SOURCE_DIR);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);

    const auto csv = read_text_csv(out / "study.csv");
    for (const char* column :
         {"run", "fluid.spacing", "solver", "particles", "steps", "wall_s", "density_error_avg_pct",
          "density_error_max_pct", "error", "status", "pareto"})
        CHECK(csv.has(column));
    REQUIRE(csv.rows.size() == 2);
    CHECK(csv.at(0, "fluid.spacing") == "0.004");
    CHECK(csv.at(1, "fluid.spacing") == "0.006");
    for (std::size_t row = 0; row < 2; ++row) {
        CHECK(csv.at(row, "status") == "ok");
        CHECK(csv.at(row, "solver") == "seed");
        CHECK(std::stod(csv.at(row, "steps")) > 0);
        CHECK(std::stod(csv.at(row, "wall_s")) > 0);
        // The scene is the dam_break_2d case: the error is mean |dZ| (large at
        // these coarse spacings, where the seed's front runs ahead).
        CHECK(std::stod(csv.at(row, "error")) >= 0);
        CHECK(fs::exists(out / "runs" /
                         (row == 0 ? "00_fluid.spacing=0.004" : "01_fluid.spacing=0.006") /
                         "stats.csv"));
    }
    CHECK(std::stoi(csv.at(0, "particles")) > std::stoi(csv.at(1, "particles")));
    CHECK((csv.at(0, "pareto") == "yes" || csv.at(1, "pareto") == "yes"));

    const std::string md = read_text(out / "study.md");
    CHECK_THAT(md, Catch::Contains("| run | `fluid.spacing`") && Catch::Contains("Martin") &&
                       Catch::Contains("study.png"));
    CHECK(sph::test::is_png(out / "study.png"));
}

TEST_CASE("a study keeps going past unstable runs, compared with the finest run", "[study][cli]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const fs::path out = tmp / "study";
    // Gravity of 1e20 m/s^2 throws particles past h in the first step, whatever
    // the solver: those runs exit 3 at once. Vectors are varied too.
    const auto result =
        run_sphclip(tmp, {"study", (tmp / "tiny.json").string(), "--vary", "solver.dt=1e-4,2e-4",
                          "--vary", "effects.gravity=[0,-9.81],[0,-1e20]", "--metric", "com",
                          "--jobs", "2", "--out", out.string()});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    const auto csv = read_text_csv(out / "study.csv");
    REQUIRE(csv.rows.size() == 4);
    CHECK(csv.at(0, "solver.dt") == "1e-4");
    CHECK(csv.at(1, "effects.gravity") == "[0,-1e20]");
    for (std::size_t row : {0, 2})
        CHECK(csv.at(row, "status") == "ok");
    for (std::size_t row : {1, 3}) {
        CHECK(csv.at(row, "status") == "unstable");
        CHECK(csv.at(row, "error").empty());
        CHECK(csv.at(row, "pareto") == "no");
    }
    // The finest: equal particle counts, the smallest time step.
    CHECK(csv.at(0, "reference") == "yes");
    CHECK(std::stod(csv.at(0, "error")) == 0);
    CHECK(std::stod(csv.at(2, "error")) > 0);
    CHECK(csv.at(2, "pareto") == "yes");
    CHECK(fs::exists(out / "runs" / "01_solver.dt=1e-4_effects.gravity=_0_-1e20_"));
    CHECK_THAT(read_text(out / "study.md"), Catch::Contains("unstable"));
    CHECK(sph::test::is_png(out / "study.png"));
}

TEST_CASE("study: bad input exits 2 before running more than once", "[study][cli]") {
    TempFolder tmp;
    write_text(tmp / "tiny.json", tiny_scene);
    const std::string scene = (tmp / "tiny.json").string();
    const std::string out = (tmp / "study").string();

    SECTION("--vary without values") {
        const auto r = run_sphclip(tmp, {"study", scene, "--vary", "fluid.spacing", "--out", out});
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains("--vary"));
    }
    SECTION("no such scene file") {
        const auto r = run_sphclip(
            tmp, {"study", (tmp / "nope.json").string(), "--vary", "fps=10,20", "--out", out});
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains("nope.json"));
    }
    SECTION("a --set without =: refused before any run") {
        const auto r =
            run_sphclip(tmp, {"study", scene, "--set", "fps", "--vary", "fps=10,20", "--out", out});
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains("--set: expected KEY=VALUE, got \"fps\""));
        CHECK_FALSE(fs::exists(fs::path(out) / "runs"));
    }
    SECTION("an unknown key: the run's own message, and only the first run tried") {
        const auto r = run_sphclip(tmp, {"study", scene, "--set", "fluid.spacingg=0.01", "--vary",
                                         "fps=10,20,30", "--jobs", "2", "--out", out});
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.output, Catch::Contains("fluid.spacingg"));
        CHECK(fs::exists(fs::path(out) / "runs" / "00_fps=10"));
        CHECK_FALSE(fs::exists(fs::path(out) / "runs" / "01_fps=20"));
    }
}
