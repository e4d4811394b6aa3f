// The numbers contract (docs/contract.md, "Numbers"): a scene whose derived
// quantities (particle mass, density, sound speed, pressure scale, time step,
// kinetic energy, gravity) would overflow or flush to zero is refused at the
// scene check (exit 2, naming the field, nothing written), and no stats.csv
// row or particle export ever holds inf or NaN.

#include "support/run_sphclip.hpp"
#include "support/small_tank.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;
using sph::test::contains;
using sph::test::read_text;
using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::write_text;

const std::string small_scene = sph::test::small_tank(0.05);

// Every cell of a CSV file, after its header, is a finite number or text
// that is not a number (hashes); "inf" or "nan" anywhere fails.
void check_all_finite(const fs::path& path) {
    const auto csv = sph::test::read_text_csv(path);
    for (const auto& row : csv.rows)
        for (const auto& cell : row) {
            INFO(path.string() << ": " << cell);
            CHECK(!contains(cell, "inf"));
            CHECK(!contains(cell, "nan"));
        }
}

} // namespace

TEST_CASE("numbers: values whose derived quantities overflow or vanish are refused naming the "
          "field",
          "[contract][numbers]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const struct {
        const char* set;
        const char* key;
    } cases[] = {
        {"fluid.mass=1e306", "fluid.mass"},
        {"fluid.blocks.0.velocity=[1e200,0]", "fluid.blocks[0].velocity"},
        {"material.rest_density=1e-300", "material.rest_density"},
        {"material.bulk_modulus=1e308", "material.bulk_modulus"},
        {"effects.gravity=[0,1e308]", "effects.gravity"},
        {"solver.dt=1e-300", "solver.dt"},
        {"solver.dt=1e-12", "solver.dt"}, // finite, but a billion steps and more
    };
    for (const auto& c : cases) {
        const fs::path out = tmp / "out";
        const auto run =
            run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out", out.string(), "--set",
                              c.set, "--export", "csv", "--no-png", "--no-mp4", "--threads", "1"});
        INFO(c.set << "\n" << run.output);
        CHECK(run.exit_code == 2);
        CHECK(contains(run.output, c.key));
        CHECK(!fs::exists(out));
    }
}

TEST_CASE("numbers: a run that blows up stops (exit 3) before any non-finite value is written",
          "[contract][numbers]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const fs::path out = tmp / "out";
    // Passes the scene check (every derived value in range), and flies
    // apart at step 171: a fixed step six times what the adaptive rule takes.
    const auto run = run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out", out.string(),
                                       "--set", "solver.dt=0.002", "--export", "csv", "--no-png",
                                       "--no-mp4", "--threads", "1"});
    INFO(run.output);
    CHECK(run.exit_code == 3);
    check_all_finite(out / "stats.csv");
    for (const auto& entry : fs::directory_iterator(out / "particles"))
        check_all_finite(entry.path());
}
