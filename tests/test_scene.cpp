// Scene parsing (src/scene/scene.cpp): defaults, the schema's checks, --set
// overrides, effects, the resolved-scene round trip and the key list.

#include "scene/input_error.hpp"
#include "scene/scene.hpp"
#include "support/text.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using sph::InputError;
using sph::Override;
using sph::Scene;

const std::string label = "test.json";

// A small valid 2D scene: 6 x 6 = 36 particles.
json small_2d() {
    return json::parse(R"({
        "domain": {"min": [0, 0], "max": [0.1, 0.1]},
        "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
        "duration": 0.05,
        "fps": 40
    })");
}

// A small valid 3D scene: 6 x 6 x 6 = 216 particles.
json small_3d() {
    return json::parse(R"({
        "dimension": 3,
        "domain": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
        "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0, 0], "max": [0.06, 0.06, 0.06]}]}
    })");
}

// `scene` with the field at a JSON pointer ("/fluid/spacing") replaced.
json with(json scene, const std::string& pointer, const json& value) {
    scene[json::json_pointer(pointer)] = value;
    return scene;
}

Scene parse(const json& scene, const std::vector<Override>& overrides = {}) {
    return sph::parse_scene(scene.dump(), label, overrides);
}

// The InputError that parsing throws, or nothing when it parses.
std::optional<InputError> error_of_text(const std::string& text,
                                        const std::vector<Override>& overrides = {}) {
    try {
        sph::parse_scene(text, label, overrides);
    } catch (const InputError& e) {
        return e;
    }
    return std::nullopt;
}

std::optional<InputError> error_of(const json& scene, const std::vector<Override>& overrides = {}) {
    return error_of_text(scene.dump(), overrides);
}

using sph::test::contains;

} // namespace

TEST_CASE("the built-in scene is the 2D dam break", "[scene]") {
    const Scene s = sph::default_scene({});
    CHECK(s.dimension == 2);
    REQUIRE(s.fluid.blocks.size() == 1);
    CHECK(s.fluid.blocks[0].min[0] == 0);
    CHECK(s.fluid.blocks[0].min[1] == 0);
    CHECK(s.fluid.blocks[0].max[0] == Approx(0.05715));
    CHECK(s.fluid.blocks[0].max[1] == Approx(0.1143));
    REQUIRE(s.effects.gravity);
    CHECK(s.effects.gravity->acceleration[1] == Approx(-9.81));

    const sph::Derived d = sph::derive(s);
    CHECK(d.particles == 40 * 80);
    CHECK(d.h == Approx(2.5 * s.fluid.spacing));
    CHECK(d.dt > 0);
    CHECK(d.mass > 0);
    CHECK(d.sound_speed == Approx(std::sqrt(s.material.bulk_modulus / s.material.rest_density)));
}

TEST_CASE("scene files may hold // and /* */ comments", "[scene]") {
    const Scene s = sph::parse_scene(R"({
        // line comment
        "fps": 24, /* block comment */
        "duration": /* inside a value's line */ 2.5
    })",
                                     label, {});
    CHECK(s.fps == 24);
    CHECK(s.duration == 2.5);
}

TEST_CASE("invalid JSON is reported with its line and column", "[scene]") {
    SECTION("a missing value") {
        const auto e = error_of_text("{\n  \"fps\": 30,\n  \"duration\": ,\n}\n");
        REQUIRE(e);
        CHECK(e->file == label);
        CHECK(e->field.empty());
        CHECK(contains(e->what(), "test.json: invalid JSON at line 3, column 15"));
    }
    SECTION("a missing comma, found on the next key's line") {
        const auto e = error_of_text("{\n\"fps\": 30\n\"duration\": 1}");
        REQUIRE(e);
        INFO(e->what());
        CHECK(contains(e->what(), "invalid JSON at line 3, column "));
    }
    SECTION("text that ends early") {
        const auto e = error_of_text("{\"fps\": 30,\n");
        REQUIRE(e);
        CHECK(contains(e->what(), "invalid JSON at line 2"));
    }
    SECTION("a scene that is not an object") {
        const auto e = error_of_text("[1, 2]");
        REQUIRE(e);
        CHECK(contains(e->what(), "JSON object"));
    }
}

TEST_CASE("an unknown key is named and the closest known key suggested", "[scene]") {
    SECTION("in a group") {
        const auto e = error_of_text(R"({"material": {"viscosty": 1}})");
        REQUIRE(e);
        CHECK(e->field == "material.viscosty");
        CHECK(contains(e->what(), "unknown key"));
        CHECK(contains(e->what(), "'material.viscosity'"));
    }
    SECTION("at the top level") {
        const auto e = error_of_text(R"({"durration": 1})");
        REQUIRE(e);
        CHECK(e->field == "durration");
        CHECK(contains(e->what(), "'duration'"));
    }
    SECTION("inside a fluid block") {
        const auto e = error_of(with(small_2d(), "/fluid/blocks/0/velocty", {0, 0}));
        REQUIRE(e);
        CHECK(e->field == "fluid.blocks[0].velocty");
        CHECK(contains(e->what(), "'fluid.blocks[0].velocity'"));
    }
    SECTION("a group given as a value") {
        const auto e = error_of_text(R"({"material": 5})");
        REQUIRE(e);
        CHECK(e->field == "material");
        CHECK(contains(e->what(), "expected an object"));
    }
}

// Fails while the unknown-key check derives a key's place in the schema from
// its text: a key spelt "blocks[0]" reads as the list element and is ignored.
TEST_CASE("a key spelt with brackets is unknown, not silently ignored", "[scene]") {
    const auto e = error_of_text(R"({"fluid": {"blocks[0]": {"max": [0.01, 0.01]}}})");
    REQUIRE(e);
    CHECK(e->field == "fluid.blocks[0]");
    CHECK(contains(e->what(), "unknown key"));
}

TEST_CASE("a value of the wrong type names the field", "[scene]") {
    SECTION("a string for a number") {
        const auto e = error_of(with(small_2d(), "/fps", "ten"));
        REQUIRE(e);
        CHECK(e->field == "fps");
        CHECK(contains(e->problem, "expected a number"));
    }
    SECTION("a fraction for an integer") {
        const auto e = error_of(with(small_2d(), "/dimension", 2.5));
        REQUIRE(e);
        CHECK(e->field == "dimension");
        CHECK(contains(e->problem, "integer"));
    }
    SECTION("a 3-vector in a 2D scene") {
        const auto e = error_of(with(small_2d(), "/domain/min", {0, 0, 0}));
        REQUIRE(e);
        CHECK(e->field == "domain.min");
        CHECK(contains(e->problem, "2 numbers"));
    }
    SECTION("a string inside a vector") {
        const auto e = error_of(with(small_2d(), "/domain/max", {0.1, "high"}));
        REQUIRE(e);
        CHECK(e->field == "domain.max[1]");
    }
    SECTION("a number for a list") {
        const auto e = error_of(with(small_2d(), "/fluid/blocks", 3));
        REQUIRE(e);
        CHECK(e->field == "fluid.blocks");
    }
    SECTION("a number for a string") {
        const auto e = error_of(with(small_2d(), "/solver/name", 1));
        REQUIRE(e);
        CHECK(e->field == "solver.name");
        CHECK(contains(e->problem, "expected a string"));
    }
}

namespace {
struct BadValue {
    const char* pointer; // where in small_2d()
    const char* value;   // JSON text
    const char* field;   // the field the error must name
    const char* problem; // a part of the problem it must state
};
} // namespace

TEST_CASE("a value out of its range names the field", "[scene]") {
    const auto bad = GENERATE(values<BadValue>({
        {"/fluid/spacing", "-0.005", "fluid.spacing", "greater than 0"},
        {"/fluid/spacing", "0", "fluid.spacing", "greater than 0"},
        {"/fps", "0", "fps", "greater than 0"},
        {"/duration", "0", "duration", "greater than 0"},
        {"/duration", "-1", "duration", "greater than 0"},
        {"/material/viscosity", "-1", "material.viscosity", "negative"},
        {"/material/rest_density", "0", "material.rest_density", "greater than 0"},
        {"/material/bulk_modulus", "-2e5", "material.bulk_modulus", "greater than 0"},
        {"/solver/dt", "0", "solver.dt", "greater than 0"},
        {"/solver/rebalance_above", "0.5", "solver.rebalance_above", "between 1 and 1000"},
        {"/solver/rebalance_above", "2000", "solver.rebalance_above", "between 1 and 1000"},
        {"/solver/momentum", "1", "solver.momentum", "below 1"},
        {"/solver/momentum", "-0.5", "solver.momentum", "negative"},
        {"/fluid/smoothing_ratio", "-2", "fluid.smoothing_ratio", "greater than 0"},
        {"/dimension", "4", "dimension", "between 2 and 3"},
        {"/dimension", "1", "dimension", "between 2 and 3"},
        {"/render/size", "[0, 720]", "render.size", "between 1 and"},
        {"/render/size", "[1280, 0]", "render.size", "between 1 and"},
        {"/render/size", "[1280]", "render.size", "2 integers"},
        {"/render/camera/fov", "180", "render.camera.fov", "3D camera key"},
        {"/domain/max", "[0.1, 0]", "domain", "min must be below max"},
        {"/domain/min", "[0.1, 0]", "domain", "min must be below max"},
        {"/fluid/blocks/0/max", "[0, 0.03]", "fluid.blocks[0]", "min must be below max"},
        {"/fluid/blocks/0/max", "[0.2, 0.03]", "fluid.blocks[0]", "outside the domain"},
        {"/fluid/blocks/0/min", "[-0.01, 0]", "fluid.blocks[0]", "outside the domain"},
        {"/fluid/blocks/0/max", "[0.003, 0.03]", "fluid.blocks[0]", "thinner than one spacing"},
        {"/fluid/blocks", "[]", "fluid.blocks", "no fluid"},
        {"/solver/name", "\"sed\"", "solver.name", "did you mean \"seed\""},
        {"/solver/neighbour_search", "\"grid\"", "solver.neighbour_search", "hash"},
        {"/render/colour", "\"velocty\"", "render.colour", "did you mean \"velocity\""},
    }));
    INFO(bad.pointer << " = " << bad.value);
    const auto e = error_of(with(small_2d(), bad.pointer, json::parse(bad.value)));
    REQUIRE(e);
    CHECK(e->file == label);
    CHECK(e->field == bad.field);
    CHECK(contains(e->problem, bad.problem));
    CHECK(std::string(e->what()) == label + ": " + e->field + ": " + e->problem);
}

// Fails while nlohmann's out_of_range (number overflow) escapes the parser:
// the program then exits 1 with a message naming neither file nor field.
TEST_CASE("a number too large for a double is bad input", "[scene]") {
    const auto e = error_of_text(R"({"fps": 1e999})");
    REQUIRE(e);
    CHECK(e->file == label);
    CHECK(contains(e->what(), "fps"));

    const auto from_set = error_of(small_2d(), {{"fps", "1e999"}});
    REQUIRE(from_set);
    CHECK(contains(from_set->what(), "fps (from --set)"));
}

TEST_CASE("an absurd particle count is refused early, with count and memory", "[scene]") {
    const auto start = std::chrono::steady_clock::now();
    const auto e = error_of(with(json::object(), "/fluid/spacing", 1e-12));
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    REQUIRE(e);
    CHECK(e->field == "fluid");
    CHECK(contains(e->problem, "particles"));
    CHECK(contains(e->problem, "GiB"));
    // Refused by arithmetic, not by trying to allocate or fill the lattice.
    CHECK(seconds < 0.5);

    // The same in 3D, where the count is larger still.
    const auto e3 = error_of(with(small_3d(), "/fluid/spacing", 1e-9));
    REQUIRE(e3);
    CHECK(e3->field == "fluid");
    CHECK(contains(e3->problem, "GiB"));
}

TEST_CASE("set overrides take numbers, arrays, objects, strings and list items", "[scene]") {
    SECTION("a number") {
        const Scene s = parse(small_2d(), {{"fps", "60"}, {"material.viscosity", "0.5"}});
        CHECK(s.fps == 60);
        CHECK(s.material.viscosity == 0.5);
    }
    SECTION("the last of several wins") {
        CHECK(parse(small_2d(), {{"fps", "10"}, {"fps", "20"}}).fps == 20);
    }
    SECTION("an array") {
        const Scene s = parse(small_2d(), {{"domain.max", "[0.2, 0.1]"}});
        CHECK(s.domain.max[0] == 0.2);
        CHECK(s.domain.max[1] == 0.1);
    }
    SECTION("an object") {
        const Scene s =
            parse(small_2d(), {{"fluid.blocks", R"([{"min": [0, 0], "max": [0.02, 0.04]},
                                                    {"min": [0.05, 0], "max": [0.07, 0.01]}])"}});
        REQUIRE(s.fluid.blocks.size() == 2);
        CHECK(s.fluid.blocks[0].max[1] == 0.04);
        CHECK(s.fluid.blocks[1].min[0] == 0.05);
        CHECK(sph::derive(s).particles == 4 * 8 + 4 * 2);
    }
    SECTION("a string, taken as text when it is not JSON") {
        const Scene s = parse(small_2d(), {{"solver.name", "seed"}, {"render.colour", "density"}});
        CHECK(s.solver.name == sph::SolverKind::seed);
        CHECK(s.render.colour == sph::ColourField::density);
    }
    SECTION("an item of a list, by its index") {
        const Scene s = parse(small_2d(), {{"fluid.blocks.0.min", "[0.01, 0]"}});
        REQUIRE(s.fluid.blocks.size() == 1);
        CHECK(s.fluid.blocks[0].min[0] == 0.01);
        CHECK(s.fluid.blocks[0].max[0] == 0.03); // the rest of the block is kept
        CHECK(sph::derive(s).particles == 4 * 6);
    }
    SECTION("a new item just past the end of a list") {
        const Scene s =
            parse(small_2d(), {{"fluid.blocks.1", R"({"min": [0.05, 0], "max": [0.07, 0.02]})"}});
        REQUIRE(s.fluid.blocks.size() == 2);
        CHECK(s.fluid.blocks[1].max[0] == 0.07);
    }
    SECTION("a field the file does not have") {
        const Scene s = parse(small_2d(), {{"solver.dt", "1e-4"}});
        REQUIRE(s.solver.dt);
        CHECK(*s.solver.dt == 1e-4);
        CHECK(sph::derive(s).dt == 1e-4);
    }
}

TEST_CASE("an error in a --set value names the field and its origin", "[scene]") {
    SECTION("out of range") {
        const auto e = error_of(small_2d(), {{"fluid.spacing", "-1"}});
        REQUIRE(e);
        CHECK(e->field == "fluid.spacing (from --set)");
        CHECK(contains(e->what(), "fluid.spacing (from --set): must be greater than 0"));
    }
    SECTION("a word where a number belongs") {
        const auto e = error_of(small_2d(), {{"fps", "fast"}});
        REQUIRE(e);
        CHECK(e->field == "fps (from --set)");
        CHECK(contains(e->problem, "expected a number"));
    }
    SECTION("an unknown key, with a suggestion") {
        const auto e = error_of(small_2d(), {{"material.viscosty", "1"}});
        REQUIRE(e);
        CHECK(contains(e->what(), "material.viscosty (from --set)"));
        CHECK(contains(e->what(), "'material.viscosity'"));
    }
    SECTION("an index past the end of a list") {
        const auto e = error_of(small_2d(), {{"fluid.blocks.5.min", "[0, 0]"}});
        REQUIRE(e);
        CHECK(contains(e->what(), "(from --set)"));
        CHECK(contains(e->problem, "past the end"));
    }
    SECTION("a list indexed by a name") {
        const auto e = error_of(small_2d(), {{"fluid.blocks.first.min", "[0, 0]"}});
        REQUIRE(e);
        CHECK(contains(e->problem, "index it with a number"));
    }
    SECTION("a number treated as a group") {
        const auto e = error_of(small_2d(), {{"fps.max", "3"}});
        REQUIRE(e);
        CHECK(contains(e->problem, "'fps' is not an object"));
    }
}

// Fails while "(from --set)" is added only when the failing path equals the
// overridden key exactly, not for an element or a block inside it.
TEST_CASE("an error inside a --set value still says it came from --set", "[scene]") {
    SECTION("an element of a vector") {
        const auto e = error_of(small_2d(), {{"domain.min", R"([0, "a"])"}});
        REQUIRE(e);
        CHECK(contains(e->what(), "domain.min[1] (from --set)"));
    }
    SECTION("a block of a list") {
        const auto e =
            error_of(small_2d(), {{"fluid.blocks", R"([{"min": [0, 0], "max": [0.5, 0.02]}])"}});
        REQUIRE(e);
        CHECK(contains(e->what(), "outside the domain"));
        CHECK(contains(e->what(), "(from --set)"));
    }
}

// Fails while apply_override turns the absent `fluid.blocks` into an object
// keyed "0" instead of a list: the built-in block cannot be edited by index.
TEST_CASE("a set override can index the built-in scene's fluid block", "[scene]") {
    const Scene s = sph::default_scene({{"fluid.blocks.0.min", "[0.01, 0]"}});
    REQUIRE(s.fluid.blocks.size() == 1);
    CHECK(s.fluid.blocks[0].min[0] == 0.01);
    CHECK(s.fluid.blocks[0].max[0] == Approx(0.05715));
}

TEST_CASE("gravity is on by default and off in an effects object without it", "[scene]") {
    SECTION("no effects key: the default gravity") {
        const Scene s = parse(small_2d());
        REQUIRE(s.effects.gravity);
        CHECK(s.effects.gravity->acceleration[0] == 0);
        CHECK(s.effects.gravity->acceleration[1] == Approx(-9.81));
    }
    SECTION("an empty effects object: no gravity") {
        CHECK_FALSE(parse(with(small_2d(), "/effects", json::object())).effects.gravity);
    }
    SECTION("gravity null: no gravity") {
        CHECK_FALSE(parse(with(small_2d(), "/effects/gravity", nullptr)).effects.gravity);
    }
    SECTION("--set effects.gravity=[0,0]: present and zero") {
        const Scene s = parse(small_2d(), {{"effects.gravity", "[0,0]"}});
        REQUIRE(s.effects.gravity);
        CHECK(s.effects.gravity->acceleration[0] == 0);
        CHECK(s.effects.gravity->acceleration[1] == 0);
    }
    SECTION("--set adds gravity to a scene whose effects have none") {
        const Scene s =
            parse(with(small_2d(), "/effects", json::object()), {{"effects.gravity", "[0,-1]"}});
        REQUIRE(s.effects.gravity);
        CHECK(s.effects.gravity->acceleration[1] == -1);
    }
}

TEST_CASE("the resolved scene reads back as the same scene", "[scene]") {
    const json scene = GENERATE(
        json::object(), small_2d(), with(small_2d(), "/effects", json::object()),
        with(with(small_3d(), "/render/camera/position", {0.3, 0.2, 0.4}), "/solver/dt", 1e-4),
        with(with(small_2d(), "/fluid/smoothing_length", 0.02), "/fluid/mass", 0.1));
    INFO(scene.dump());
    const Scene first = parse(scene);
    const json resolved = sph::to_json(first);
    const Scene second = sph::parse_scene(resolved.dump(), "run.json", {});
    CHECK(sph::to_json(second) == resolved);

    // Derived values are filled in.
    const sph::Derived d = sph::derive(first);
    CHECK(resolved["fluid"]["mass"].get<double>() == d.mass);
    CHECK(resolved["fluid"]["smoothing_length"].get<double>() == d.h);
    // A fixed step reads back as itself; an adaptive one stays adaptive.
    CHECK(resolved["solver"]["dt"].is_null() == !d.fixed_dt);
    if (d.fixed_dt)
        CHECK(resolved["solver"]["dt"].get<double>() == d.dt);
}

TEST_CASE("scene_keys documents every key of the scene format", "[scene]") {
    const auto keys = sph::scene_keys();
    for (const char* name :
         {"dimension", "duration", "fps", "domain.min", "domain.max", "fluid.spacing",
          "fluid.blocks", "material.rest_density", "material.bulk_modulus", "material.viscosity",
          "solver.name", "solver.dt", "effects.gravity", "render.size", "render.colour"}) {
        INFO(name);
        const auto it = std::find_if(keys.begin(), keys.end(),
                                     [&](const sph::KeyDoc& k) { return k.path == name; });
        REQUIRE(it != keys.end());
        CHECK_FALSE(it->description.empty());
        CHECK_FALSE(it->type.empty());
    }
    for (const auto& k : keys) {
        INFO(k.path);
        CHECK_FALSE(k.description.empty());
        CHECK(std::count_if(keys.begin(), keys.end(),
                            [&](const sph::KeyDoc& other) { return other.path == k.path; }) == 1);
    }
}

TEST_CASE("3D scenes take 3-vectors and refuse 2-vectors", "[scene]") {
    const Scene s = parse(small_3d());
    CHECK(s.dimension == 3);
    CHECK(s.domain.max[2] == 0.1);
    REQUIRE(s.effects.gravity);
    CHECK(s.effects.gravity->acceleration[1] == Approx(-9.81));
    const sph::Derived d = sph::derive(s);
    CHECK(d.particles == 6 * 6 * 6);
    CHECK(d.h == Approx(2.2 * 0.01));

    SECTION("a 2-vector for the domain") {
        const auto e = error_of(with(small_3d(), "/domain/min", {0, 0}));
        REQUIRE(e);
        CHECK(e->field == "domain.min");
        CHECK(contains(e->problem, "3 numbers"));
    }
    SECTION("a 2-vector for a block") {
        const auto e = error_of(with(small_3d(), "/fluid/blocks/0/max", {0.06, 0.06}));
        REQUIRE(e);
        CHECK(e->field == "fluid.blocks[0].max");
    }
    SECTION("a 2-vector from --set") {
        const auto e = error_of(small_3d(), {{"effects.gravity", "[0, -9.81]"}});
        REQUIRE(e);
        CHECK(e->field == "effects.gravity (from --set)");
    }
}

// Each fails while the value slips past the checks (NaN compares false with
// every limit) or overflows a cast or a loop in derive().
TEST_CASE("extreme numbers are refused before anything is allocated", "[scene]") {
    struct Extreme {
        const char* name;
        json scene;
        const char* field;   // the field the error must name
        const char* problem; // a part of the problem it must state
    };
    const auto start = std::chrono::steady_clock::now();
    const auto extreme = GENERATE(values<Extreme>({
        {"1e45 particles in 3D, far below the coordinate limit",
         json::parse(R"({"dimension": 3, "domain": {"min": [0, 0, 0], "max": [1e7, 1e7, 1e7]},
                         "fluid": {"spacing": 1e-8,
                                   "blocks": [{"min": [0, 0, 0], "max": [1e7, 1e7, 1e7]}]}})"),
         "fluid", "1e+45 particles"},
        {"1e300 m blocks", json::parse(R"({"domain": {"min": [0, 0], "max": [1e300, 1e300]},
                         "fluid": {"blocks": [{"min": [0, 0], "max": [1e300, 1e300]}]}})"),
         "domain", "too far from the origin"},
        {"a domain wider than the largest double",
         json::parse(R"({"domain": {"min": [-1e308, 0], "max": [1e308, 1]},
                         "fluid": {"spacing": 1e300, "blocks": [{"min": [0, 0], "max": [1, 1]}]}})"),
         "domain", "beyond the range of a double"},
        {"0 particles on one axis times infinitely many on the other",
         json::parse(R"({"domain": {"min": [0, 0], "max": [1e-300, 1e300]},
                         "fluid": {"spacing": 1e290, "smoothing_ratio": 10,
                                   "blocks": [{"min": [0, 0], "max": [1e-300, 1e300]}]}})"),
         "fluid.blocks[0]", "thinner than one spacing"},
        {"a support of 1e300 spacings", with(json::object(), "/fluid/smoothing_ratio", 1e300),
         "fluid.smoothing_ratio", "spacings"},
        {"a support of 1000 spacings (a lattice sum of 2e9 terms)",
         with(with(json::object(), "/dimension", 3), "/fluid/smoothing_ratio", 1000),
         "fluid.smoothing_ratio", "must be 1 to 20"},
        {"a support below one spacing", with(json::object(), "/fluid/smoothing_length", 1e-300),
         "fluid.smoothing_length", "no neighbour"},
        {"1e308 s of clip", with(json::object(), "/duration", 1e308), "duration", "frames"},
        {"a mass beyond a double", json::parse(R"({"domain": {"min": [0, 0], "max": [100, 100]},
                         "material": {"rest_density": 1e308},
                         "fluid": {"spacing": 10, "blocks": [{"min": [0, 0], "max": [50, 50]}]}})"),
         "material.rest_density", "particle mass"},
        {"a mass that rounds to 0", with(json::object(), "/material/rest_density", 1e-320),
         "material.rest_density", "particle mass"},
        {"an infinite speed of sound",
         with(with(json::object(), "/material/bulk_modulus", 1e308), "/material/rest_density",
              1e-10),
         "material.bulk_modulus", "speed of sound"},
        {"boundary particles in a 10 km tank", json::parse(R"({"solver": {"name": "wcsph"},
                         "domain": {"min": [0, 0, 0], "max": [1e4, 1e4, 1e4]}, "dimension": 3,
                         "fluid": {"spacing": 0.01,
                                   "blocks": [{"min": [0, 0, 0], "max": [0.05, 0.05, 0.05]}]}})"),
         "domain", "boundary particles"},
    }));
    INFO(extreme.name);
    const auto e = error_of(extreme.scene);
    REQUIRE(e);
    INFO(e->what());
    CHECK(e->field == extreme.field);
    CHECK(contains(e->problem, extreme.problem));
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 0.5);
}

TEST_CASE("a refused particle count names the count and the memory it needs", "[scene]") {
    const auto e = error_of(with(json::object(), "/fluid/spacing", 1e-12));
    REQUIRE(e);
    CHECK(e->field == "fluid");
    // 0.05715 m x 0.1143 m at 1e-12 m: 6.53e21 particles.
    CHECK(contains(e->problem, "6.53e+21 particles"));
    CHECK(contains(e->problem, "GiB of memory"));
}

TEST_CASE("output.name names the output folder under out/", "[scene]") {
    SECTION("by default the scene's name") {
        CHECK_FALSE(parse(small_2d()).output.name);
        CHECK(sph::output_folder(parse(small_2d())) == "out/default");
        CHECK(sph::to_json(parse(small_2d()))["output"]["name"] == "default");
    }
    SECTION("a relative path inside out/") {
        const Scene s = parse(with(small_2d(), "/output/name", "studies/run 1"));
        REQUIRE(s.output.name);
        CHECK(sph::output_folder(s) == "out/studies/run 1");
        CHECK(sph::to_json(s)["output"]["name"] == "studies/run 1");
    }
    SECTION("a name leading outside out/ is refused") {
        for (const char* name : {"../escape", "/tmp/escape", "a/../../b", ""}) {
            INFO(name);
            const auto e = error_of(with(small_2d(), "/output/name", name));
            REQUIRE(e);
            CHECK(e->file == label);
            CHECK(e->field == "output.name");
            CHECK(contains(e->problem, "inside out/"));
        }
    }
    SECTION("also from --set, which says so") {
        const auto e = error_of(small_2d(), {{"output.name", "../../etc"}});
        REQUIRE(e);
        CHECK(e->field == "output.name (from --set)");
    }
    SECTION("a name that is not a string, or not UTF-8") {
        const auto number = error_of(with(small_2d(), "/output/name", 3));
        REQUIRE(number);
        CHECK(contains(number->problem, "expected a string"));
        const auto bytes = error_of(small_2d(), {{"output.name", "caf\xe9"}});
        REQUIRE(bytes);
        CHECK(contains(bytes->problem, "UTF-8"));
    }
    SECTION("a scene file whose own name would leave out/") {
        Scene s = parse(small_2d());
        s.name = ".."; // the stem of "...json"
        CHECK_THROWS_AS(sph::output_folder(s), InputError);
    }
}

// Fails while an unknown key or value of megabytes is compared letter by
// letter with every known one, or dumped whole into the message.
TEST_CASE("a huge unknown key, value or nesting is refused quickly and briefly", "[scene]") {
    const auto start = std::chrono::steady_clock::now();
    const std::string long_word(1 << 20, 'k');
    const auto key = error_of_text("{\"" + long_word + "\": 1}");
    REQUIRE(key);
    CHECK(contains(key->problem, "unknown key"));
    const auto value = error_of_text("{\"solver\": {\"name\": \"" + long_word + "\"}}");
    REQUIRE(value);
    CHECK(value->problem.size() < 300);
    const std::string deep = std::string(100000, '[') + std::string(100000, ']');
    const auto nested = error_of_text("{\"fps\": " + deep + "}");
    REQUIRE(nested);
    CHECK(nested->field == "fps");
    CHECK(nested->problem.size() < 200);
    CHECK(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() < 5);
}
