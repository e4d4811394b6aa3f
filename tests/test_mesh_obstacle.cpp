// Mesh obstacles (src/sph/triangle_mesh.*, src/scene/obj_mesh.*, the mesh case
// of src/sph/boundaries/obstacles.cpp and of the scene's effects.obstacles): a cube mesh
// against the analytic box, an icosphere against the analytic sphere, the
// OBJ file's checks and path rule, a dam break that never puts fluid inside,
// and the renderer.
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "scene/input_error.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene.hpp"
#include "scene/scene_setup.hpp"
#include "sph/boundaries/obstacles.hpp"
#include "sph/boundaries/triangle_mesh.hpp"
#include "support/temp_folder.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <vector>

using namespace sph;
using nlohmann::json;
using sph::test::TempFolder;
using sph::test::write_text;

namespace {

// The box [lo, hi] as 8 vertices and 12 triangles, counter-clockwise seen
// from outside unless `inward`.
std::string cube_obj(const Vec<3>& lo, const Vec<3>& hi, bool inward = false) {
    std::string text = "# a box\n";
    for (int k = 0; k < 8; ++k)
        text += fmt::format("v {} {} {}\n", k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y,
                            k & 4 ? hi.z : lo.z);
    // Two triangles per face, 1-based; each quad counter-clockwise from outside.
    const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                             {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (const auto& q : quads) {
        if (inward) {
            text += fmt::format("f {} {} {}\nf {} {} {}\n", q[0], q[2], q[1], q[0], q[3], q[2]);
        } else {
            text += fmt::format("f {} {} {}\nf {} {} {}\n", q[0], q[1], q[2], q[0], q[2], q[3]);
        }
    }
    return text;
}

// An icosphere of radius 1 at the origin: `subdivisions` times each triangle
// split in four, the new vertices pushed onto the sphere.
std::string icosphere_obj(int subdivisions) {
    const Real t = (1 + std::sqrt(Real(5))) / 2;
    std::vector<Vec<3>> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                             {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                             {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : v)
        p = glm::normalize(p);
    std::vector<Triangle> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto it = middle.find(key);
            if (it != middle.end())
                return it->second;
            v.push_back(glm::normalize(v[a] + v[b]));
            return middle[key] = std::uint32_t(v.size() - 1);
        };
        std::vector<Triangle> split;
        for (const Triangle& f : faces) {
            const std::uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                                ca = midpoint(f[2], f[0]);
            split.insert(split.end(),
                         {{f[0], ab, ca}, {f[1], bc, ab}, {f[2], ca, bc}, {ab, bc, ca}});
        }
        faces = split;
    }
    std::string text;
    for (const auto& p : v)
        text += fmt::format("v {:.17g} {:.17g} {:.17g}\n", p.x, p.y, p.z);
    for (const Triangle& f : faces)
        text += fmt::format("f {} {} {}\n", f[0] + 1, f[1] + 1, f[2] + 1);
    return text;
}

std::shared_ptr<const TriangleMesh> mesh_from(const TempFolder& folder, const std::string& text,
                                              Real scale = 1, Vec<3> offset = Vec<3>(0)) {
    write_text(folder / "mesh.obj", text);
    return read_obj_mesh(folder / "mesh.obj", scale, offset, "test.json", "mesh");
}

Obstacle<3> box_obstacle(const Vec<3>& lo, const Vec<3>& hi) {
    return {ObstacleShape::box, {lo, hi}, Vec<3>(0), 0, nullptr};
}

Obstacle<3> mesh_obstacle(std::shared_ptr<const TriangleMesh> mesh) {
    return {ObstacleShape::mesh, {}, Vec<3>(0), 0, std::move(mesh)};
}

// A 3D tank whose scene file sits in `folder`, with one mesh obstacle.
json tank_with_mesh(const std::string& file = "cube.obj") {
    return json::parse(fmt::format(R"({{
        "dimension": 3, "duration": 0.2, "fps": 20,
        "domain": {{"min": [0, 0, 0], "max": [0.12, 0.2, 0.12]}},
        "fluid": {{"spacing": 0.01, "blocks": [{{"min": [0.02, 0.1, 0.02], "max": [0.1, 0.18, 0.1]}}]}},
        "solver": {{"name": "wcsph"}},
        "effects": {{"gravity": [0, -9.81, 0],
                    "obstacles": [{{"mesh": {{"file": "{}"}}}}]}}
    }})",
                                   file));
}

Scene load(const TempFolder& folder, const json& scene) {
    write_text(folder / "scene.json", scene.dump(2));
    return load_scene(folder / "scene.json", {});
}

} // namespace

TEST_CASE("a cube mesh's signed distance is the box obstacle's", "[obstacles][mesh]") {
    const TempFolder folder;
    const Vec<3> lo(0.1, 0.2, 0.3), hi(0.25, 0.3, 0.5);
    const Obstacle<3> box = box_obstacle(lo, hi);
    for (const bool inward : {false, true}) {
        INFO((inward ? "clockwise" : "counter-clockwise") << " faces");
        const Obstacle<3> mesh = mesh_obstacle(mesh_from(folder, cube_obj(lo, hi, inward)));
        CHECK(mesh.mesh->volume() == Approx(0.15 * 0.1 * 0.2));
        CHECK(mesh.mesh->area() == Approx(2 * (0.15 * 0.1 + 0.15 * 0.2 + 0.1 * 0.2)));
        std::mt19937 random(7);
        std::uniform_real_distribution<Real> around(-0.1, 0.1);
        int inside = 0;
        for (int k = 0; k < 20000; ++k) {
            // Around the box, and some points snapped onto its faces, edges
            // and corners' planes, where the feature that is nearest changes.
            Vec<3> x;
            for (int a = 0; a < 3; ++a) {
                x[a] = 0.5 * (lo[a] + hi[a]) + (hi[a] - lo[a]) * around(random) * 8;
                if (k % 5 == a)
                    x[a] = k % 2 ? lo[a] : hi[a];
            }
            const Real expected = box.signed_distance(x);
            INFO("x = (" << x.x << ", " << x.y << ", " << x.z << ")");
            REQUIRE(mesh.signed_distance(x) == Approx(expected).margin(1e-12));
            CHECK(mesh.nearer_than(x, 0.01) == (expected < 0.01));
            inside += expected < 0;
        }
        CHECK(inside > 1000);
        // The closest point and the normal on a face.
        const auto near = mesh.mesh->nearest({0.2, 0.29, 0.4});
        CHECK(near.point.y == Approx(0.3));
        CHECK(near.normal.y == Approx(1));
        CHECK(near.distance == Approx(-0.01));
    }
}

TEST_CASE("an icosphere mesh's signed distance is the sphere's, within its facets",
          "[obstacles][mesh]") {
    const TempFolder folder;
    const Real radius = 0.05;
    const Vec<3> centre(0.1, 0.1, 0.1);
    const Obstacle<3> mesh = mesh_obstacle(mesh_from(folder, icosphere_obj(4), radius, centre));
    REQUIRE(mesh.mesh->triangles().size() == 5120);
    // The flat facets lie inside the sphere by at most its sagitta:
    // R (1 - cos(theta)), theta about the edge's angle, 0.03 rad here.
    const Real sagitta = 2e-3 * radius;
    std::mt19937 random(3);
    std::uniform_real_distribution<Real> uniform(-1, 1);
    for (int k = 0; k < 20000; ++k) {
        const Vec<3> x =
            centre + 2 * radius * Vec<3>(uniform(random), uniform(random), uniform(random));
        const Real exact = glm::length(x - centre) - radius;
        const Real d = mesh.signed_distance(x);
        REQUIRE(d >= exact - 1e-12);
        REQUIRE(d <= exact + sagitta);
    }
}

TEST_CASE("a cube mesh is sampled exactly as the box obstacle", "[obstacles][mesh]") {
    const TempFolder folder;
    const Real s = 0.01, h = 0.022; // 3 layers
    struct Case {
        Vec<3> lo, hi;
    };
    // On the fluid's lattice; sides that are not whole spacings (a stretched
    // lattice); a cube thinner than two shells (solid throughout).
    for (const Case& c : {Case{{0.1, 0.2, 0.3}, {0.2, 0.3, 0.42}},
                          Case{{0.013, 0.02, 0.031}, {0.0915, 0.0985, 0.11}},
                          Case{{0, 0, 0}, {0.04, 0.05, 0.03}}}) {
        const std::vector<Obstacle<3>> box{box_obstacle(c.lo, c.hi)};
        const std::vector<Obstacle<3>> mesh{mesh_obstacle(mesh_from(folder, cube_obj(c.lo, c.hi)))};
        const auto expected = sample_obstacles<3>(box, s, h, 0.9e-6);
        const auto got = sample_obstacles<3>(mesh, s, h, 0.9e-6);
        REQUIRE(got.positions.size() == expected.positions.size());
        CHECK(got.positions.size() >= 60);
        // The same sites in the same order (rows along x, then y, then z).
        for (std::size_t b = 0; b < got.positions.size(); ++b) {
            INFO("sample " << b);
            REQUIRE(glm::length(got.positions[b] - expected.positions[b]) < 1e-12);
            REQUIRE(got.volumes[b] == Approx(expected.volumes[b]).epsilon(1e-12));
        }
    }
}

TEST_CASE("a mesh's samples lie in its shell, and leave out other obstacles", "[obstacles][mesh]") {
    const TempFolder folder;
    const Real s = 0.005, h = 0.011; // 3 layers
    const auto ball = mesh_from(folder, icosphere_obj(3), 0.05, Vec<3>(0.1, 0.1, 0.1));
    const std::vector<Obstacle<3>> alone{mesh_obstacle(ball)};
    const auto samples = sample_obstacles<3>(alone, s, h, 1.25e-7);
    // About the shell's volume over the cell's: (R^3 - (R - 3s)^3) 4 pi / 3 / s^3.
    const Real shell = 4 * M_PI / 3 * (std::pow(0.05, 3) - std::pow(0.05 - 3 * s, 3)) / (s * s * s);
    CHECK(Real(samples.positions.size()) == Approx(shell).epsilon(0.05));
    for (const auto& x : samples.positions) {
        const Real d = alone[0].signed_distance(x);
        REQUIRE(d < 0);
        REQUIRE(d > -3 * s - 1e-12);
    }
    // Half of it inside a box: those samples go.
    const std::vector<Obstacle<3>> both{mesh_obstacle(ball),
                                        box_obstacle(Vec<3>(0.1, 0, 0), Vec<3>(0.2, 0.2, 0.2))};
    const auto joined = sample_obstacles<3>(both, s, h, 1.25e-7);
    for (const auto& x : joined.positions)
        REQUIRE(!(both[0].signed_distance(x) < 0 && both[1].signed_distance(x) < 0));
}

TEST_CASE("a particle inside a mesh is put back on its surface", "[obstacles][mesh]") {
    const TempFolder folder;
    const std::vector<Obstacle<3>> mesh{
        mesh_obstacle(mesh_from(folder, icosphere_obj(2), 0.05, Vec<3>(0.1, 0.1, 0.1)))};
    State<3> state;
    state.resize(3);
    state.position = {{0.1, 0.14, 0.1}, {0.1, 0.2, 0.1}, {0.06, 0.1, 0.1}};
    state.velocity = {{0, -1, 0}, {0, -1, 0}, {0.5, 0, 0.5}};
    CHECK(push_out_of_obstacles<3>(mesh, state) == 2);
    for (std::size_t i = 0; i < state.size(); ++i) {
        const Real d = mesh[0].signed_distance(state.position[i]);
        CHECK(d >= 0);
    }
    CHECK(mesh[0].signed_distance(state.position[0]) < 1e-12);
    // Its velocity into the solid reflected: now moving out, along +y.
    CHECK(state.velocity[0].y > 0.9);
    CHECK(state.velocity[1].y == -1); // outside: untouched
    CHECK(state.velocity[2].x < 0);
    CHECK(state.velocity[2].z == Approx(0.5).margin(0.1));
}

TEST_CASE("mesh obstacles are read from the scene, relative to its folder", "[obstacles][mesh]") {
    const TempFolder folder;
    std::filesystem::create_directories(folder / "meshes");
    write_text(folder / "meshes" / "cube.obj", cube_obj(Vec<3>(-1), Vec<3>(1)));
    json scene = tank_with_mesh("meshes/cube.obj");
    scene["effects"]["obstacles"][0]["mesh"]["scale"] = 0.02;
    scene["effects"]["obstacles"][0]["mesh"]["offset"] = {0.06, 0.12, 0.06}; // in the block
    const Scene s = load(folder, scene);
    REQUIRE(s.effects.obstacles.size() == 1);
    const SceneObstacle& o = s.effects.obstacles[0];
    CHECK(o.shape == ObstacleShape::mesh);
    REQUIRE(o.mesh);
    CHECK(o.mesh->bounds().min.x == Approx(0.04));
    CHECK(o.mesh->bounds().max.y == Approx(0.14));
    // run.json records the keys as given; read back they give the same scene.
    const json resolved = to_json(s);
    CHECK(resolved["effects"]["obstacles"][0]["mesh"]["file"] == "meshes/cube.obj");
    CHECK(resolved["effects"]["obstacles"][0]["mesh"]["scale"] == 0.02);
    write_text(folder / "run.json", resolved.dump());
    CHECK(to_json(load_scene(folder / "run.json", {})) == resolved);
    // Fluid sites inside, or within half a spacing of, the mesh are left out.
    const auto sim = make_simulation<3>(s);
    for (const auto& x : sim.state().position)
        REQUIRE(sim.params().obstacles[0].signed_distance(x) >= 0.5 * 0.01 - 1e-9);
    CHECK(sim.state().size() < derive(s).particles);
}

TEST_CASE("bad mesh obstacles are refused with file and field", "[obstacles][mesh]") {
    const TempFolder folder;
    const Vec<3> lo(0.04, 0, 0.04), hi(0.08, 0.04, 0.08);
    write_text(folder / "cube.obj", cube_obj(lo, hi));
    std::string open = cube_obj(lo, hi);
    open.erase(open.rfind("f "));
    write_text(folder / "open.obj", open);
    write_text(folder / "twice.obj", cube_obj(lo, hi) + "f 1 3 4\n");
    // The last face's two triangles wound the other way.
    std::string flipped = cube_obj(lo, hi);
    flipped.replace(flipped.rfind("f ", flipped.rfind("f ") - 1), std::string::npos,
                    "f 2 8 4\nf 2 6 8\n");
    write_text(folder / "flipped.obj", flipped);
    write_text(folder / "empty.obj", "# nothing\nv 0 0 0\nv 1 0 0\n");
    write_text(folder / "binary.obj", std::string("\x7f"
                                                  "ELF\x02\x01\x01\0\0\0",
                                                  10));
    write_text(folder / "flat.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 3 2\n");
    write_text(folder / "big.obj", cube_obj(Vec<3>(0), Vec<3>(1)));
    const std::string field = "effects.obstacles[0].mesh";
    struct Case {
        const char* what;
        json scene;
        std::string field, message;
    };
    auto with_file = [&](const std::string& name) {
        return tank_with_mesh(name);
    };
    json in_2d = json::parse(R"({
        "domain": {"min": [0, 0], "max": [0.2, 0.1]},
        "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0], "max": [0.2, 0.05]}]},
        "solver": {"name": "wcsph"},
        "effects": {"obstacles": [{"mesh": {"file": "cube.obj", "offset": [0, 0]}}]}
    })");
    json no_file = tank_with_mesh();
    no_file["effects"]["obstacles"][0]["mesh"] = {{"scale", 2}};
    json zero_scale = tank_with_mesh();
    zero_scale["effects"]["obstacles"][0]["mesh"]["scale"] = 0;
    json seed = tank_with_mesh();
    seed["solver"]["name"] = "seed";
    const Case cases[] = {
        {"a missing file", with_file("nothing.obj"), field + ".file", "cannot read the mesh file"},
        {"a folder", with_file("."), field + ".file", "itself"},
        {"a path out of the scene's folder", with_file("../cube.obj"), field + ".file",
         "climbs out with \"..\""},
        {"an absolute path", with_file((folder / "cube.obj").string()), field + ".file",
         "it is absolute"},
        {"an open mesh", with_file("open.obj"), field + ".file", "not closed: 3 edges"},
        {"an edge of three faces", with_file("twice.obj"), field + ".file", "not a manifold"},
        {"faces turned both ways", with_file("flipped.obj"), field + ".file",
         "not consistently oriented"},
        {"no faces", with_file("empty.obj"), field + ".file", "no triangles"},
        {"not an OBJ file", with_file("binary.obj"), field + ".file", "no triangles"},
        {"no volume", with_file("flat.obj"), field + ".file", "encloses no volume"},
        {"a mesh in 2D", in_2d, field, "a 2D scene has boxes and spheres"},
        {"no file key", no_file, field + ".file", "needs the OBJ file's name"},
        {"a zero scale", zero_scale, field + ".scale", "greater than 0"},
        {"outside the domain", with_file("big.obj"), field, "outside the domain"},
        {"the seed solver", seed, "effects.obstacles", "solver.name=wcsph or dfsph"},
    };
    for (const Case& c : cases) {
        INFO(c.what << ": " << c.scene.dump());
        std::optional<InputError> error;
        try {
            load(folder, c.scene);
        } catch (const InputError& e) {
            error = e;
        }
        REQUIRE(error);
        INFO(error->what());
        CHECK(error->file == (folder / "scene.json").string());
        CHECK(error->field == c.field);
        CHECK(error->problem.find(c.message) != std::string::npos);
    }
    // The good one loads.
    CHECK_NOTHROW(load(folder, with_file("cube.obj")));
}

TEST_CASE("sphclip keys lists the mesh obstacle keys", "[obstacles][mesh]") {
    const auto keys = scene_keys();
    for (const char* name : {"effects.obstacles[].mesh.file", "effects.obstacles[].mesh.scale",
                             "effects.obstacles[].mesh.offset"}) {
        INFO(name);
        const auto it =
            std::find_if(keys.begin(), keys.end(), [&](const KeyDoc& k) { return k.path == name; });
        REQUIRE(it != keys.end());
        CHECK_FALSE(it->description.empty());
    }
}

namespace {

// The smallest signed distance of any fluid particle to any obstacle.
Real closest_approach(const Simulation<3>& sim) {
    Real closest = std::numeric_limits<Real>::infinity();
    for (const auto& x : sim.state().position)
        for (const auto& o : sim.params().obstacles)
            closest = std::min(closest, o.signed_distance(x));
    return closest;
}

} // namespace

TEST_CASE("a 3D block falling on a mesh obstacle never puts fluid inside it", "[obstacles][mesh]") {
    const TempFolder folder;
    // An icosphere, and a tilted cube (a mesh that is not axis-aligned).
    write_text(folder / "ball.obj", icosphere_obj(2));
    const Real c = std::cos(0.5), s = std::sin(0.5);
    std::string tilted;
    for (int k = 0; k < 8; ++k) {
        const Real x = k & 1 ? 1 : -1, y = k & 2 ? 1 : -1, z = k & 4 ? 1 : -1;
        tilted += fmt::format("v {} {} {}\n", c * x - s * y, s * x + c * y, z);
    }
    const std::string cube = cube_obj(Vec<3>(0), Vec<3>(1));
    tilted += cube.substr(cube.find("f "));
    write_text(folder / "tilted.obj", tilted);
    for (const char* file : {"ball.obj", "tilted.obj"}) {
        for (const char* solver : {"wcsph", "dfsph"}) {
            INFO(file << ", " << solver);
            json scene = tank_with_mesh(file);
            scene["solver"]["name"] = solver;
            scene["material"]["viscosity"] = 0.001;
            scene["duration"] = 0.2;
            scene["effects"]["obstacles"][0]["mesh"]["scale"] = 0.025;
            scene["effects"]["obstacles"][0]["mesh"]["offset"] = {0.06, 0.05, 0.06};
            auto sim = make_simulation<3>(load(folder, scene));
            const std::size_t n = sim.state().size();
            for (int k = 1; k <= 4; ++k) {
                sim.advance_to(0.05 * k);
                INFO("t = " << sim.time() << " s");
                REQUIRE(sim.state().size() == n);
                REQUIRE(closest_approach(sim) >= 0);
            }
        }
    }
}

TEST_CASE("the renderer draws a mesh obstacle solid", "[obstacles][mesh]") {
    const TempFolder folder;
    write_text(folder / "ball.obj", icosphere_obj(2));
    json scene = tank_with_mesh("ball.obj");
    scene["effects"]["obstacles"][0]["mesh"]["scale"] = 0.04;
    scene["effects"]["obstacles"][0]["mesh"]["offset"] = {0.06, 0.05, 0.06};
    scene["render"] = {{"size", {320, 180}}};
    const Scene s = load(folder, scene);
    auto sim = make_simulation<3>(s);
    sim.update_fields();
    Snapshot frame;
    copy_fields(sim.state(), frame);
    auto context = make_gl_context("auto");
    // The mesh is lit grey-beige (r >= g >= b): count the pixels of that
    // kind that the obstacle changes, against the same frame without it.
    // Left of the colour bar only, whose yellow end would count.
    auto draw = [&](const RenderSettings& settings) {
        FrameRenderer renderer(settings);
        return renderer.render(frame);
    };
    RenderSettings settings = make_render_settings(s);
    REQUIRE(settings.obstacles.size() == 1);
    for (const char* background : {"light", "dark"}) {
        INFO(background);
        settings.background = *choice_named<Background>(background);
        RenderSettings without = settings;
        without.obstacles.clear();
        const Image with_mesh = draw(settings), bare = draw(without);
        std::size_t solid = 0, changed = 0;
        for (int y = 0; y < with_mesh.height; ++y)
            for (int x = 0; x < 200; ++x) {
                const std::uint8_t* p = with_mesh.pixel(x, y);
                const std::uint8_t* q = bare.pixel(x, y);
                const bool differs =
                    std::abs(p[0] - q[0]) + std::abs(p[1] - q[1]) + std::abs(p[2] - q[2]) > 6;
                changed += differs;
                solid += differs && p[0] > 40 && p[0] >= p[1] && p[1] >= p[2] && p[0] - p[2] >= 3;
            }
        CHECK(solid > 500);
        // The mesh is drawn solid: most of what it changes is its own colour.
        CHECK(solid > changed / 2);
    }
}

TEST_CASE("the shipped mesh scene loads and starts clear of its boulder", "[obstacles][mesh]") {
    const Scene scene =
        load_scene(std::string(SPHCLIP_SOURCE_DIR) + "/scenes/dam_break_mesh_3d.json", {});
    REQUIRE(scene.effects.obstacles.size() == 1);
    const auto& mesh = scene.effects.obstacles[0].mesh;
    REQUIRE(mesh);
    CHECK(mesh->triangles().size() == 1280);
    CHECK(mesh->bounds().min.y == Approx(0).margin(1e-12));
    auto sim = make_simulation<3>(scene);
    CHECK(sim.state().size() == 15 * 25 * 25);
    CHECK(closest_approach(sim) > 0.05);
}
