#pragma once
// Shared by the renderer's tests (test_render.cpp, test_surface_mesh.cpp):
// a tiny two-block scene, its first frame drawn on a chosen backend, and the
// check of an image against its golden under tests/golden/
// (SPHCLIP_UPDATE_GOLDEN=1 rewrites the goldens: look at them before
// committing).

#include "output/image_compare.hpp"
#include "output/png_io.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"
#include "scene/scene_setup.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sph::test {

// A small block moving right and a smaller one falling, coloured by speed
// with some variety; `more` is applied last.
inline Scene tiny_scene(int dimension, const std::vector<Override>& more = {}) {
    std::vector<Override> o{{"render.size", "[320,180]"}};
    if (dimension == 2) {
        o.push_back({"domain.max", "[0.1,0.06]"});
        o.push_back({"fluid.spacing", "0.004"});
        o.push_back({"fluid.blocks", R"([{"min":[0,0],"max":[0.04,0.04],"velocity":[0.4,0]},
                                         {"min":[0.06,0.03],"max":[0.08,0.05],"velocity":[0,-1]}])"});
    } else {
        o.push_back({"dimension", "3"});
        o.push_back({"domain.max", "[0.1,0.06,0.05]"});
        o.push_back({"fluid.spacing", "0.005"});
        o.push_back({"fluid.blocks",
                     R"([{"min":[0,0,0],"max":[0.04,0.04,0.05],"velocity":[0.4,0,0]},
                         {"min":[0.06,0.03,0.01],"max":[0.08,0.05,0.03],"velocity":[0,-1,0]}])"});
    }
    o.insert(o.end(), more.begin(), more.end());
    return default_scene(o);
}

// The scene's state at t = 0, with its fields, as a run's frame 0.
template <int D>
Snapshot initial_snapshot(const Scene& scene) {
    auto sim = make_simulation<D>(scene);
    sim.update_fields();
    Snapshot s;
    s.frame = 0;
    s.time = 0;
    s.stats = measure_frame(sim.params(), sim.state());
    copy_fields(sim.state(), s);
    return s;
}

// Frame 0 of `scene` drawn on `backend` ("egl", "osmesa", "auto").
inline Image render_scene(const Scene& scene, std::string_view backend) {
    auto context = make_gl_context(backend);
    FrameRenderer renderer(make_render_settings(scene));
    return scene.dimension == 2 ? renderer.render(initial_snapshot<2>(scene))
                                : renderer.render(initial_snapshot<3>(scene));
}

// `image` matches tests/golden/NAME.png as `sphclip compare` decides; on a
// mismatch the image is left in the temporary folder to look at.
inline void check_against_golden(const Image& image, const std::string& name) {
    namespace fs = std::filesystem;
    const fs::path golden = fs::path(SPHCLIP_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
    if (std::getenv("SPHCLIP_UPDATE_GOLDEN")) {
        fs::create_directories(golden.parent_path());
        write_png(golden, image);
        WARN("rewrote " << golden);
    }
    REQUIRE(fs::exists(golden));
    const CompareResult result = compare_images(read_png(golden), image, CompareOptions{});
    INFO(name << ": mean difference " << result.mean_difference << ", different "
              << result.different_percent << "%");
    if (!result.match)
        write_png(fs::temp_directory_path() / (name + "_failed.png"), image);
    CHECK(result.match);
}

} // namespace sph::test
