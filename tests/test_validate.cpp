// `sphclip validate`: the surge front and the hydrostatic profile on
// synthetic particles (src/analysis/surge_front.*, hydrostatic_profile.*,
// csv_table.*), then the command end to end on coarse versions of the cases.

#include "analysis/csv_table.hpp"
#include "analysis/gravity_current.hpp"
#include "analysis/hydrostatic_profile.hpp"
#include "analysis/surge_front.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::ParticleFrame;
using sph::test::read_text_csv;
using sph::test::run_sphclip;
using sph::test::TempFolder;

// A 2D block of nx x ny particles on the lattice min + (k + 1/2) s, at rest,
// at density rho and pressure p(y).
template <class Pressure>
ParticleFrame lattice_2d(int nx, int ny, double s, double rho, Pressure p) {
    ParticleFrame f;
    f.dimension = 2;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const double x = (i + 0.5) * s, y = (j + 0.5) * s;
            f.position.insert(f.position.end(), {x, y});
            f.velocity.insert(f.velocity.end(), {0.0, 0.0});
            f.density.push_back(rho);
            f.pressure.push_back(p(y));
        }
    return f;
}

void add_particle(ParticleFrame& f, double x, double y) {
    f.position.insert(f.position.end(), {x, y});
    f.velocity.insert(f.velocity.end(), {0.0, 0.0});
    f.density.push_back(1000);
    f.pressure.push_back(0);
}

} // namespace

TEST_CASE("CSV tables are read by column name, skipping comments", "[validate]") {
    const auto table =
        sph::parse_csv_table("# a comment\nT,extra,Z\n0.5,x,1.5\n# more\n1,2,3\n4,5\n", "test.csv");
    REQUIRE(table.rows() == 3);
    CHECK(table.column("T") == std::vector<double>{0.5, 1, 4});
    CHECK(std::isnan(table.column("extra")[0]));
    CHECK(table.column("Z")[1] == 3);
    CHECK(std::isnan(table.column("Z")[2])); // a short row is padded
    CHECK_THROWS_WITH(table.column("nope"), Catch::Contains("test.csv") && Catch::Contains("nope"));
}

TEST_CASE("the surge front is the edge of the fluid body, not of its spray", "[validate]") {
    const double s = 0.01;
    auto frame = lattice_2d(5, 10, s, 1000, [](double) { return 0.0; });
    // The initial column: Z = 1 exactly, measured from the wall at 0.
    CHECK(sph::surge_front_distance(frame, s, 0.0) == Approx(0.05));
    // A droplet far ahead is ignored; a particle touching the front is not.
    add_particle(frame, 0.3, 0.005);
    CHECK(sph::surge_front_distance(frame, s, 0.0) == Approx(0.05));
    add_particle(frame, 0.06, 0.005);
    CHECK(sph::surge_front_distance(frame, s, 0.0) == Approx(0.065));
    // Measured from the wall.
    CHECK(sph::surge_front_distance(frame, s, -0.01) == Approx(0.075));
}

TEST_CASE("surge-front series are interpolated linearly and compared in range", "[validate]") {
    const std::vector<sph::SurgeSample> simulated{{0, 1}, {1, 2}, {2, 4}};
    CHECK(sph::interpolate_Z(simulated, 0.5) == Approx(1.5));
    CHECK(sph::interpolate_Z(simulated, 1.5) == Approx(3));
    CHECK(sph::interpolate_Z(simulated, 2) == Approx(4));
    CHECK(sph::interpolate_Z(simulated, 0) == Approx(1));
    CHECK(std::isnan(sph::interpolate_Z(simulated, 2.5)));
    CHECK(std::isnan(sph::interpolate_Z({}, 1)));

    // Reference points at T = 0.5 (dZ = 0.1), 1.5 (dZ = -0.5) and 3 (out of range).
    const std::vector<sph::SurgeSample> reference{{0.5, 1.4}, {1.5, 3.5}, {3, 5}};
    const auto c = sph::compare_surge_front(simulated, reference);
    REQUIRE(c.points.size() == 2);
    CHECK(c.points[1].Z_simulated == Approx(3));
    CHECK(c.mean_abs_dZ == Approx(0.3));
    CHECK(c.max_abs_dZ == Approx(0.5));
    CHECK(std::isnan(sph::compare_surge_front(simulated, {{5, 1}}).mean_abs_dZ));
}

TEST_CASE("the Martin & Moyce table ships in the repository's data/reference", "[validate]") {
    const fs::path table = fs::path(SPHCLIP_SOURCE_DIR) / "data" / "reference" /
                           "martin_moyce_1952_surge_front_table2.csv";
    REQUIRE(fs::exists(table));
    // Its source is named in its header.
    CHECK(sph::test::read_text(table).starts_with("# Martin J.C. & Moyce W.J. (1952)"));
    const auto reference = sph::read_surge_reference(table);
    REQUIRE(reference.size() >= 10);
    for (std::size_t i = 1; i < reference.size(); ++i) {
        CHECK(reference[i].T > reference[i - 1].T);
        CHECK(reference[i].Z > reference[i - 1].Z);
    }
}

TEST_CASE("pressure against depth on a synthetic tank", "[validate]") {
    const double s = 0.005, rho0 = 1000, g = 9.81;
    const double H = 20 * s; // 20 layers: the free surface at 0.1 m
    const sph::HydrostaticSetup setup{rho0, g, s, 0.0};

    SECTION("exact hydrostatic pressure: no error") {
        const auto f = lattice_2d(10, 20, s, rho0, [&](double y) { return rho0 * g * (H - y); });
        CHECK(sph::free_surface_height(f, s) == Approx(H));
        const auto r = sph::analyse_hydrostatic(f, setup);
        CHECK(r.fluid_depth == Approx(H));
        CHECK(r.bottom_pressure == Approx(rho0 * g * H));
        CHECK(r.bins.size() == 20);
        CHECK(r.pressure_error_rms_pct == Approx(0).margin(1e-9));
        CHECK(r.density_error_avg_pct == Approx(0).margin(1e-12));
        CHECK(r.speed_max == 0);
    }
    SECTION("a constant offset is that offset in percent of the bottom pressure") {
        const double offset = 0.05 * rho0 * g * H;
        const auto f =
            lattice_2d(10, 20, s, 1010, [&](double y) { return rho0 * g * (H - y) + offset; });
        const auto r = sph::analyse_hydrostatic(f, setup);
        CHECK(r.pressure_error_rms_pct == Approx(5));
        CHECK(r.pressure_error_max_pct == Approx(5));
        CHECK(r.density_error_avg_pct == Approx(1));
    }
    SECTION("the surface is the mean over columns of their top particle") {
        auto f = lattice_2d(10, 20, s, rho0, [](double) { return 0.0; });
        // Columns are two spacings wide: particles at x < 0.01 are column 0.
        for (int i = 0; i < 10; i += 4) {
            add_particle(f, (i + 0.5) * s, H + 0.5 * s);
            add_particle(f, (i + 1.5) * s, H + 0.5 * s);
        }
        const double raised = 3.0 / 5.0; // columns 0, 2 and 4 of 5
        CHECK(sph::free_surface_height(f, s) == Approx(H + raised * s));
    }
    SECTION("residual speeds") {
        auto f = lattice_2d(2, 2, s, rho0, [](double) { return 0.0; });
        f.velocity = {3, 4, 0, 1, 0, 0, 0, 0};
        const auto r = sph::analyse_hydrostatic(f, setup);
        CHECK(r.speed_max == Approx(5));
        CHECK(r.speed_mean == Approx(1.5));
    }
}

TEST_CASE("validate runs coarse cases, scores them and writes tables and plots",
          "[validate][cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "v";
    // Coarse and short: a few hundred particles each, 0.2 s (T up to 3.7).
    const auto result =
        run_sphclip(tmp,
                    {"validate", "hydrostatic_2d", "dam_break_2d", "--out", out.string(), "--set",
                     "fluid.spacing=0.005", "--set", "duration=0.2", "--jobs", "2"},
                    SPHCLIP_SOURCE_DIR);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK_THAT(result.output, Catch::Contains("dam_break_2d") && Catch::Contains("mean|dZ|=") &&
                                  Catch::Contains("p_err_rms="));

    const auto summary = read_text_csv(out / "summary.csv");
    REQUIRE(summary.rows.size() == 2);
    for (const char* column : {"case", "solver", "status", "particles", "steps", "wall_s",
                               "mean_abs_dZ", "pressure_error_rms_pct", "verdict"})
        CHECK(summary.has(column));
    CHECK(summary.at(0, "case") == "hydrostatic_2d");
    CHECK(summary.at(1, "status") == "completed");
    CHECK(std::stod(summary.at(1, "mean_abs_dZ")) >= 0);
    CHECK(summary.at(0, "mean_abs_dZ").empty());
    CHECK(std::stod(summary.at(0, "pressure_error_rms_pct")) >= 0);

    const auto surge = sph::read_csv_table(out / "dam_break_2d" / "surge_front.csv");
    CHECK(surge.rows() == 21); // frames 0..20: validate runs dam breaks at 100 fps
    CHECK(surge.column("Z")[0] == Approx(1));
    const auto compared =
        sph::read_csv_table(out / "dam_break_2d" / "surge_front_vs_reference.csv");
    CHECK(compared.rows() >= 5);
    CHECK(sph::read_csv_table(out / "hydrostatic_2d" / "pressure_depth.csv").rows() >= 15);
    CHECK(sph::test::is_png(out / "dam_break_2d" / "surge_front.png"));
    CHECK(sph::test::is_png(out / "hydrostatic_2d" / "pressure_depth.png"));
    CHECK(fs::exists(out / "hydrostatic_2d" / "metrics.json"));
}

TEST_CASE("a spreading current's half width and Huppert's front", "[validate]") {
    const double s = 0.01;
    auto frame = lattice_2d(6, 3, s, 1000, [](double) { return 0.0; });
    CHECK(sph::spreading_half_width(frame, s) == Approx(0.03)); // the block's own
    add_particle(frame, 0.5, 0.005);                            // spray: ignored
    CHECK(sph::spreading_half_width(frame, s) == Approx(0.03));
    add_particle(frame, -0.01, 0.005); // fluid touching the left edge
    CHECK(sph::spreading_half_width(frame, s) == Approx(0.0375));
    // x_N = 1.411 (g A^3 t / 3 nu)^(1/5); grows as t^(1/5).
    CHECK(sph::huppert_front(9.81, 0.003, 10.0 / 1420, 1.0) == Approx(0.14763).epsilon(1e-4));
    CHECK(sph::huppert_front(9.81, 0.003, 10.0 / 1420, 32.0) ==
          Approx(2 * sph::huppert_front(9.81, 0.003, 10.0 / 1420, 1.0)));
}

TEST_CASE("validate scores a viscous spread against Huppert (1982)", "[validate][cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "v";
    const auto result = run_sphclip(tmp,
                                    {"validate", "honey_spread_2d", "--out", out.string(), "--set",
                                     "fluid.spacing=0.005", "--set", "duration=1.2"},
                                    SPHCLIP_SOURCE_DIR);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK_THAT(result.output, Catch::Contains("front_err_mean=") && Catch::Contains("PASS"));
    const auto summary = read_text_csv(out / "summary.csv");
    REQUIRE(summary.rows.size() == 1);
    CHECK(std::stod(summary.at(0, "front_error_mean_pct")) < 5);
    CHECK(summary.at(0, "mean_abs_dZ").empty());
    const auto front = sph::read_csv_table(out / "honey_spread_2d" / "spreading_front.csv");
    CHECK(front.rows() == 12); // frames 1..12 at 10 fps
    CHECK(sph::test::is_png(out / "honey_spread_2d" / "spreading_front.png"));
}

TEST_CASE("validate: an unknown case exits 2 listing the cases", "[validate][cli]") {
    TempFolder tmp;
    const auto result =
        run_sphclip(tmp, {"validate", "dam_break_4d", "--out", (tmp / "v").string()});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.output, Catch::Contains("dam_break_4d") && Catch::Contains("hydrostatic_3d"));
    CHECK(!fs::exists(tmp / "v"));
}

TEST_CASE("validate: a --set without = exits 2 before any run", "[validate][cli]") {
    TempFolder tmp;
    const auto result = run_sphclip(
        tmp, {"validate", "hydrostatic_2d", "--set", "fps", "--out", (tmp / "v").string()});
    CHECK(result.exit_code == 2);
    CHECK_THAT(result.output, Catch::Contains("--set: expected KEY=VALUE, got \"fps\""));
    CHECK(!fs::exists(tmp / "v"));
}

TEST_CASE("validate: an unstable run exits 3 and is reported", "[validate][cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "v";
    // Gravity of 1e20 m/s^2 throws particles past h in the first step, whatever the solver.
    const auto result = run_sphclip(tmp,
                                    {"validate", "dam_break_2d", "--out", out.string(), "--set",
                                     "fluid.spacing=0.005", "--set", "effects.gravity=[0,-1e20]"},
                                    SPHCLIP_SOURCE_DIR);
    INFO(result.output);
    CHECK(result.exit_code == 3);
    CHECK_THAT(result.output, Catch::Contains("unstable"));
    const auto summary = read_text_csv(out / "summary.csv");
    REQUIRE(summary.rows.size() == 1);
    CHECK(summary.at(0, "status") == "unstable");
}

TEST_CASE("validate needs no folder outside the repository, from any current folder",
          "[validate][cli]") {
    // From an empty folder: the scenes and the reference table are found
    // beside the program (build/../scenes, build/../data/reference), not in
    // a ../shared folder.
    TempFolder tmp;
    const fs::path out = tmp / "v";
    const auto result = run_sphclip(tmp,
                                    {"validate", "dam_break_2d", "--out", out.string(), "--set",
                                     "fluid.spacing=0.005", "--set", "duration=0.1"},
                                    tmp.path());
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(fs::exists(out / "dam_break_2d" / "surge_front_vs_reference.csv"));
    const auto summary = read_text_csv(out / "summary.csv");
    REQUIRE(summary.rows.size() == 1);
    CHECK(std::stod(summary.at(0, "mean_abs_dZ")) >= 0);
}
