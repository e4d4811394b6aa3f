// render.camera's keys (src/scene/keys/render_keys.cpp): keys of the other
// dimension (the camera's, and the 3D-only light, floor and tank keys), a
// camera looking at itself and bad keyframes are refused, each
// naming its key; paths and orbits read back from run.json's scene. And end
// to end: the camera run.json records for a clip's first and last frames,
// pasted into the scene, draws that frame again, byte for byte.

#include "render/render_settings.hpp"
#include "scene/input_error.hpp"
#include "scene/scene.hpp"
#include "support/run_sphclip.hpp"
#include "support/text.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

namespace {

using nlohmann::json;
using sph::InputError;
using sph::test::contains;

const char* const scene_2d = R"({
    "domain": {"min": [0, 0], "max": [0.1, 0.06]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "duration": 0.1, "fps": 20,
    "render": {"size": [160, 96]}
})";
const char* const scene_3d = R"({
    "dimension": 3,
    "domain": {"min": [0, 0, 0], "max": [0.1, 0.08, 0.06]},
    "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0, 0], "max": [0.04, 0.05, 0.06]}]},
    "duration": 0.1, "fps": 20,
    "render": {"size": [160, 96]}
})";

std::optional<InputError> error_of(const char* base, const std::string& pointer,
                                   const json& value) {
    json scene = json::parse(base);
    scene[json::json_pointer(pointer)] = value;
    try {
        sph::parse_scene(scene.dump(), "test.json", {});
    } catch (const InputError& e) {
        return e;
    }
    return std::nullopt;
}

struct Refused {
    const char* base;
    const char* pointer;
    const char* value;
    const char* field;
    const char* problem;
};

} // namespace

TEST_CASE("camera keys of the other dimension, and bad cameras, name their key", "[scene]") {
    const auto bad = GENERATE(values<Refused>({
        // Was silently ignored: a 3D camera on a 2D scene.
        {scene_2d, "/render/camera/position", "[0.1, 0.1, 0.3]", "render.camera.position",
         "3D camera key"},
        {scene_2d, "/render/camera/target", "[0.1, 0.1, 0]", "render.camera.target", "3D"},
        {scene_2d, "/render/camera/fov", "30", "render.camera.fov", "3D"},
        {scene_2d, "/render/camera/up", "[0, 0, 1]", "render.camera.up", "3D"},
        {scene_2d, "/render/camera/orbit", "{\"turns\": 1}", "render.camera.orbit", "3D"},
        {scene_2d, "/render/camera/aspect", "1.5", "render.camera.aspect", "3D"},
        {scene_3d, "/render/camera/aspect", "0", "render.camera.aspect", "greater than 0"},
        // Were silently ignored too: the light's, the floor's and the tank's
        // keys, and the buried particles' skip, all 3D only.
        {scene_2d, "/render/shadows", "true", "render.shadows", "3D key"},
        {scene_2d, "/render/ambient_occlusion", "true", "render.ambient_occlusion", "3D key"},
        {scene_2d, "/render/floor", "true", "render.floor", "3D key"},
        {scene_2d, "/render/tank", "false", "render.tank", "3D key"},
        {scene_2d, "/render/cull_buried", "false", "render.cull_buried", "3D key"},
        {scene_3d, "/render/camera/centre", "[0.05, 0.03]", "render.camera.centre", "2D"},
        {scene_3d, "/render/camera/height", "0.1", "render.camera.height", "2D"},
        // Issue 18: a camera at its target has no direction.
        {scene_3d, "/render/camera/position", "[0.05, 0.04, 0.03]", "render.camera.position",
         "equals the camera's target"},
        {scene_3d, "/render/camera/fov", "180", "render.camera.fov", "below 180"},
        {scene_3d, "/render/camera/up", "[0, 0, 0]", "render.camera.up", "zero"},
        {scene_3d, "/render/camera/fit", "\"fluids\"", "render.camera.fit", "\"fluid\""},
        {scene_3d, "/render/camera/path",
         R"([{"time": 1, "position": [1, 1, 1], "target": [0, 0, 0]},
             {"time": 0.5, "position": [1, 2, 1], "target": [0, 0, 0]}])",
         "render.camera.path[1].time", "must increase"},
        {scene_3d, "/render/camera/path",
         R"([{"time": 0, "position": [1, 1, 1], "target": [0, 0, 0]},
             {"time": 1, "position": [0, 0, 0], "target": [0, 0, 0]}])",
         "render.camera.path[1].position", "equals the keyframe's target"},
        {scene_3d, "/render/camera/path", R"([{"time": 0, "position": [1, 1, 1]}])",
         "render.camera.path[0].target", "needs position and target"},
        {scene_3d, "/render/camera/path", R"([{"position": [1, 1, 1], "target": [0, 0, 0]}])",
         "render.camera.path[0].time", "required"},
        {scene_3d, "/render/camera/path",
         R"([{"time": -1, "position": [1, 1, 1], "target": [0, 0, 0]}])",
         "render.camera.path[0].time", "negative"},
        {scene_2d, "/render/camera/path",
         R"([{"time": 0, "centre": [0, 0], "height": 0.1, "position": [1, 1, 1]}])",
         "render.camera.path[0].position", "3D key"},
        {scene_2d, "/render/camera/path", R"([{"time": 0, "centre": [0, 0]}])",
         "render.camera.path[0].height", "centre and height"},
        {scene_3d, "/render/camera/orbit", R"({"elevation_deg": 95})",
         "render.camera.orbit.elevation_deg", "between -89 and 89"},
        {scene_3d, "/render/camera/orbit", R"({"distance": 0})", "render.camera.orbit.distance",
         "greater than 0"},
    }));
    INFO(bad.pointer << " = " << bad.value);
    const auto e = error_of(bad.base, bad.pointer, json::parse(bad.value));
    REQUIRE(e);
    CHECK(e->field == bad.field);
    CHECK(contains(e->problem, bad.problem));
}

TEST_CASE("a path or an orbit with a fixed camera is refused", "[scene]") {
    json scene = json::parse(scene_3d);
    scene["render"]["camera"] = json::parse(R"({"position": [1, 1, 1], "orbit": {}})");
    CHECK_THROWS_AS(sph::parse_scene(scene.dump(), "test.json", {}), InputError);
    scene["render"]["camera"] = json::parse(
        R"({"orbit": {}, "path": [{"time": 0, "position": [1, 1, 1], "target": [0, 0, 0]}]})");
    try {
        sph::parse_scene(scene.dump(), "test.json", {});
        FAIL("accepted");
    } catch (const InputError& e) {
        CHECK(e.field == "render.camera.path");
    }
}

TEST_CASE("a camera path and an orbit read back from the resolved scene", "[scene]") {
    for (const char* camera :
         {R"({"path": [{"time": 0, "position": [1, 1, 1], "target": [0, 0, 0]},
                      {"time": 0.5, "position": [1, 2, 1], "target": [0, 0.1, 0], "fov": 30,
                       "up": [0, 1, 0.1]}]})",
          R"({"fit": "follow", "orbit": {"turns": -0.5, "elevation_deg": 10}})"}) {
        INFO(camera);
        json scene = json::parse(scene_3d);
        scene["render"]["camera"] = json::parse(camera);
        const sph::Scene s = sph::parse_scene(scene.dump(), "test.json", {});
        const json resolved = sph::to_json(s);
        const sph::Scene again = sph::parse_scene(resolved.dump(), "test.json", {});
        CHECK(sph::to_json(again) == resolved);
        const sph::RenderSettings r = sph::make_render_settings(again);
        CHECK_FALSE(r.camera_fixed);
    }
    // A 2D scene's resolved camera and render hold only 2D keys: it reads back.
    const sph::Scene flat = sph::parse_scene(scene_2d, "test.json", {});
    const json resolved = sph::to_json(flat);
    CHECK_FALSE(resolved["render"]["camera"].contains("fov"));
    for (const char* key : {"shadows", "ambient_occlusion", "floor", "tank", "cull_buried"})
        CHECK_FALSE(resolved["render"].contains(key));
    CHECK_NOTHROW(sph::parse_scene(resolved.dump(), "test.json", {}));
    // ... and a 3D scene's keep them.
    json deep = json::parse(scene_3d);
    deep["render"]["shadows"] = true;
    deep["render"]["floor"] = false;
    const json resolved_3d = sph::to_json(sph::parse_scene(deep.dump(), "test.json", {}));
    CHECK(resolved_3d["render"].at("shadows") == true);
    CHECK(resolved_3d["render"].at("floor") == false);
    CHECK(resolved_3d["render"].at("tank") == true);
}

TEST_CASE("a 3D-only render key on a 2D scene stops the run with exit 2, naming it",
          "[cli][scene]") {
    sph::test::TempFolder tmp;
    sph::test::write_text(tmp / "flat.json", scene_2d);
    for (const char* set : {"render.shadows=true", "render.ambient_occlusion=true",
                            "render.floor=false", "render.tank=true", "render.cull_buried=true"}) {
        INFO(set);
        const auto result = sph::test::run_sphclip(tmp, {"run", (tmp / "flat.json").string(),
                                                         "--out", (tmp / "out").string(),
                                                         "--no-mp4", "--quiet", "--set", set});
        CHECK(result.exit_code == 2);
        const std::string key(set, std::string(set).find('='));
        CHECK(contains(result.output, key));
        CHECK(contains(result.output, "3D key"));
        CHECK_FALSE(std::filesystem::exists(tmp / "out" / "frames"));
    }
}

TEST_CASE("the camera run.json records, pasted back, draws the same frame", "[cli][render]") {
    // OSMesa draws the same bytes on every machine; the clip's last frame
    // under follow (2D and 3D), a path and an orbit.
    struct Case {
        const char* name;
        const char* base;
        const char* camera;
    };
    const auto c = GENERATE(values<Case>({
        {"follow 2D", scene_2d, R"({"fit": "follow"})"},
        {"follow 3D", scene_3d, R"({"fit": "follow"})"},
        {"orbit", scene_3d, R"({"orbit": {"turns": 0.3}})"},
        {"path", scene_3d,
         R"({"path": [{"time": 0, "position": [0.3, 0.2, 0.3], "target": [0.05, 0.03, 0.03]},
                      {"time": 0.2, "position": [-0.1, 0.3, 0.3], "target": [0.05, 0, 0.03]}]})"},
    }));
    INFO(c.name);
    sph::test::TempFolder tmp;
    json scene = json::parse(c.base);
    scene["render"]["camera"] = json::parse(c.camera);
    sph::test::write_text(tmp / "moving.json", scene.dump());
    const auto first = sph::test::run_sphclip(
        tmp, {"run", (tmp / "moving.json").string(), "--out", (tmp / "moving").string(), "--no-mp4",
              "--quiet", "--threads", "1", "--backend", "osmesa"});
    INFO(first.output);
    REQUIRE(first.exit_code == 0);
    const json run = json::parse(sph::test::read_text(tmp / "moving" / "run.json"));
    const json& camera = run.at("camera");
    CHECK(camera.at("last_frame") == 2);
    CHECK(camera.at("frames") == "camera.csv");
    CHECK(sph::test::read_text(tmp / "moving" / "camera.csv").size() > 0);
    // The last frame's camera, pasted as the scene's fixed camera.
    scene["render"]["camera"] = camera.at("last");
    sph::test::write_text(tmp / "fixed.json", scene.dump());
    const auto second = sph::test::run_sphclip(
        tmp, {"run", (tmp / "fixed.json").string(), "--out", (tmp / "fixed").string(), "--no-mp4",
              "--quiet", "--threads", "1", "--backend", "osmesa"});
    INFO(second.output);
    REQUIRE(second.exit_code == 0);
    const std::string moved = sph::test::read_text(tmp / "moving" / "frames" / "frame_00002.png");
    const std::string fixed = sph::test::read_text(tmp / "fixed" / "frames" / "frame_00002.png");
    CHECK(moved.size() > 1000);
    CHECK(moved == fixed);
    // The pasted camera is recorded as it was given.
    const json again = json::parse(sph::test::read_text(tmp / "fixed" / "run.json"));
    CHECK(again.at("camera").at("first") == camera.at("last"));
    // The first frame's camera, pasted, draws the first frame again.
    scene["render"]["camera"] = camera.at("first");
    sph::test::write_text(tmp / "start.json", scene.dump());
    const auto third = sph::test::run_sphclip(tmp, {"run", (tmp / "start.json").string(), "--out",
                                                    (tmp / "start").string(), "--no-mp4", "--quiet",
                                                    "--threads", "1", "--backend", "osmesa"});
    INFO(third.output);
    REQUIRE(third.exit_code == 0);
    CHECK(sph::test::read_text(tmp / "moving" / "frames" / "frame_00000.png") ==
          sph::test::read_text(tmp / "start" / "frames" / "frame_00000.png"));
}
