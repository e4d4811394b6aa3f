// The renderer's settings from a scene (src/render/render_settings.*): each
// colour field's default range follows from the scene's physics, an explicit
// range is used as given, and a run whose frames fall mostly outside the
// range says so on stderr and in run.json.
#include "render/render_settings.hpp"
#include "scene/scene.hpp"
#include "support/run_sphclip.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>

using namespace sph;
namespace fs = std::filesystem;

namespace {

fs::path shipped(const std::string& name) {
    return fs::path(SPHCLIP_SOURCE_DIR) / "scenes" / (name + ".json");
}

} // namespace

TEST_CASE("each colour field has its own default range from the scene's physics", "[render]") {
    // The inlet at 1 m/s, 0.18 m above the floor: a particle falling from
    // its top reaches sqrt(1 + 2 g 0.18) = 2.12 m/s.
    const double fastest = std::sqrt(1.0 + 2 * 9.81 * 0.18);
    const Scene speed = load_scene(shipped("emitter_fill_2d"), {});
    const RenderSettings v = make_render_settings(speed);
    CHECK(v.range[0] == 0);
    CHECK(v.range[1] == Approx(fastest));
    CHECK(v.range_key.empty());
    CHECK(v.label == "speed (m/s)");

    // Density around rho0, +- twice the squared Mach number of that speed
    // (c^2 = K / rho0 = 200 m^2/s^2), at least 1%.
    const Scene density = load_scene(shipped("emitter_fill_2d"), {{"render.colour", "density"}});
    const RenderSettings d = make_render_settings(density);
    const double compression = std::max(0.01, 2 * fastest * fastest / 200);
    CHECK(compression > 0.04);
    CHECK(d.range[0] == Approx(1000 * (1 - compression)));
    CHECK(d.range[1] == Approx(1000 * (1 + compression)));
    CHECK(d.label == "density (kg/m^3)");
    CHECK(d.colour_map == ColourMap::diverging);

    // Pressure 0 .. rho0 g H under the 2D dam break's still column.
    const Scene dam = load_scene(shipped("dam_break_2d"), {{"render.colour", "pressure"}});
    const double column = dam.fluid.blocks[0].max[1];
    CHECK(make_render_settings(dam).range[1] == Approx(1000 * 9.81 * column));

    // Zero gravity and fluid at rest: the gentle 0.1 m/s and its dynamic
    // pressure, not the speed range.
    const Scene drop = load_scene(shipped("zero_gravity_drop_3d"), {{"render.colour", "pressure"}});
    Scene drop_default = drop;
    drop_default.render.range.reset();
    CHECK(make_render_settings(drop_default).range[1] == Approx(0.5 * 1000 * 0.1 * 0.1));
}

TEST_CASE("the default speed range holds a dam break's front, a jet's fall and a pool's",
          "[render]") {
    const double g = 9.81;
    // A column with room beside it breaks: Ritter's front, 2 sqrt(g H),
    // H the column's height.
    const Scene dam = load_scene(shipped("dam_break_2d"), {});
    const double column = dam.fluid.blocks[0].max[1];
    CHECK(make_render_settings(dam).range[1] == Approx(2 * std::sqrt(g * column)));
    // The same in 3D, where the block spans the tank's depth but not its
    // length.
    const Scene dam_3d = load_scene(shipped("dam_break_3d"), {});
    CHECK(make_render_settings(dam_3d).range[1] ==
          Approx(2 * std::sqrt(g * dam_3d.fluid.blocks[0].max[1])));
    // A pool filling the floor only falls: sqrt(2 g H). The drop above it,
    // thrown down at 0.5 m/s with its top 0.17 m up, breaks as a column:
    // sqrt(0.5^2 + 4 g 0.17).
    const Scene drop = load_scene(shipped("drop_3d"), {});
    CHECK(make_render_settings(drop).range[1] == Approx(std::sqrt(0.25 + 4 * g * 0.17)));
    const Scene pool = load_scene(shipped("hydrostatic_2d"), {{"render.colour", "velocity"}});
    CHECK(make_render_settings(pool).range[1] == Approx(std::sqrt(2 * g * 0.1)));
    // Pressure keeps the fall's speed: rho0 g H under the column.
    const Scene dam_pressure = load_scene(shipped("dam_break_2d"), {{"render.colour", "pressure"}});
    CHECK(make_render_settings(dam_pressure).range[1] == Approx(1000 * g * column));
}

TEST_CASE("the shipped 2D dam break's default run stays inside its default speed range",
          "[render][cli]") {
    // With the fall's sqrt(2 g H) as the top, the front ran above it and
    // the scene's first run warned.
    const test::TempFolder tmp;
    const test::ProgramResult run =
        test::run_sphclip(tmp, {"run", shipped("dam_break_2d").string(), "--out",
                                (tmp / "out").string(), "--duration", "0.3", "--fps", "30",
                                "--no-mp4", "--quiet", "--set", "render.size=[160,90]"});
    REQUIRE(run.exit_code == 0);
    INFO(run.output);
    CHECK(run.output.find("outside the colour range") == std::string::npos);
}

TEST_CASE("an explicit range is used as given, and names its key", "[render]") {
    const Scene scene = load_scene(shipped("emitter_fill_2d"),
                                   {{"render.colour", "density"}, {"render.range", "[0, 2.5]"}});
    const RenderSettings r = make_render_settings(scene);
    CHECK(r.range == std::array<double, 2>{0, 2.5});
    CHECK(r.range_key == "render.range");
}

TEST_CASE("a run whose particles fall outside the colour range warns once, on stderr and in "
          "run.json",
          "[render][cli]") {
    const test::TempFolder tmp;
    auto run = [&](const std::string& out, const std::vector<std::string>& extra) {
        std::vector<std::string> args{"run",        shipped("emitter_fill_2d").string(),
                                      "--out",      (tmp / out).string(),
                                      "--duration", "0.1",
                                      "--fps",      "20",
                                      "--no-mp4",   "--quiet",
                                      "--set",      "render.size=[160,90]",
                                      "--set",      "render.colour=density"};
        args.insert(args.end(), extra.begin(), extra.end());
        return test::run_sphclip(tmp, args);
    };
    // The speed range kept for density: every particle is far below it.
    const test::ProgramResult bad = run("bad", {"--set", "render.range=[0,2.5]"});
    REQUIRE(bad.exit_code == 0);
    INFO(bad.output);
    const std::string line = "warning: frame 0 (t = 0 s): 100% of the drawn particles have a "
                             "density (kg/m^3) outside the colour range [0, 2.5] (0% below, 100% "
                             "above; set by render.range)";
    CHECK(bad.output.find(line) != std::string::npos);
    // Once a run, though every frame has it.
    CHECK(bad.output.find("warning", bad.output.find(line) + line.size()) == std::string::npos);
    const auto json = nlohmann::json::parse(test::read_text(tmp / "bad" / "run.json"));
    REQUIRE(json.contains("warnings"));
    REQUIRE(json["warnings"].size() == 1);
    CHECK(json["warnings"][0].get<std::string>().find("render.range") != std::string::npos);

    // The speed's own default: no warning. (Density's default warns here:
    // the thin layer's top row, short of neighbours, is 2.5% under rho0.)
    const test::ProgramResult good = run("good", {"--set", "render.colour=velocity"});
    REQUIRE(good.exit_code == 0);
    INFO(good.output);
    CHECK(good.output.find("warning") == std::string::npos);
    CHECK_FALSE(
        nlohmann::json::parse(test::read_text(tmp / "good" / "run.json")).contains("warnings"));
}
