// src/render/render_sink: the pipelined path (encoder on a worker thread)
// writes the same PNG and MP4 bytes as the sequential one (STYLE.md point 13),
// and reports what each frame cost.

#include "output/mp4_writer.hpp"
#include "render/gl_context.hpp"
#include "render/render_sink.hpp"
#include "scene/scene_setup.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <string>
#include <vector>

using namespace sph;
namespace fs = std::filesystem;

namespace {

// Two blocks colliding in a small box: motion the encoder has to follow.
Scene small_scene() {
    return default_scene({{"render.size", "[320,180]"},
                          {"domain.max", "[0.1,0.06]"},
                          {"fluid.spacing", "0.004"},
                          {"fluid.blocks",
                           R"([{"min":[0,0],"max":[0.04,0.04],"velocity":[0.8,0]},
                               {"min":[0.06,0.03],"max":[0.08,0.05],"velocity":[0,-1]}])"}});
}

std::vector<Snapshot> frames_of(const Scene& scene, int count, double fps) {
    auto sim = make_simulation<2>(scene);
    std::vector<Snapshot> frames;
    for (int k = 0; k < count; ++k) {
        sim.advance_to(k / fps);
        sim.update_fields();
        Snapshot s;
        s.frame = std::uint64_t(k);
        s.time = sim.time();
        s.stats = measure_frame(sim.params(), sim.state());
        copy_fields(sim.state(), s);
        frames.push_back(std::move(s));
    }
    return frames;
}

std::vector<FrameCost> write_clip(const Scene& scene, const std::vector<Snapshot>& frames,
                                  const fs::path& out, EncodeThread encode) {
    RenderSink sink(make_gl_context("auto"), make_render_settings(scene), out / "frames",
                    out / "clip.mp4", 30, Mp4Options{}, encode);
    for (const auto& frame : frames)
        sink.write(frame);
    sink.finish();
    return sink.costs();
}

} // namespace

TEST_CASE("the encoder on its own thread writes the same frames and video as the sequential path",
          "[render][pipeline]") {
    if (!Mp4Writer::available())
        return;
    sph::test::TempFolder tmp;
    const Scene scene = small_scene();
    const std::vector<Snapshot> frames = frames_of(scene, 8, 30);
    const auto sequential =
        write_clip(scene, frames, tmp / "sequential", EncodeThread::same_thread);
    const auto pipelined = write_clip(scene, frames, tmp / "pipelined", EncodeThread::worker);

    const std::string video = sph::test::read_text(tmp / "sequential" / "clip.mp4");
    REQUIRE(video.size() > 1000);
    // Extra parentheses: Catch prints no megabytes of binary on failure.
    CHECK((sph::test::read_text(tmp / "pipelined" / "clip.mp4") == video));
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const std::string png = fmt::format("frames/frame_{:05d}.png", k);
        INFO(png);
        CHECK((sph::test::read_text(tmp / "pipelined" / png) ==
               sph::test::read_text(tmp / "sequential" / png)));
    }

    // Every frame's costs, the encoder's included (measured where it ran).
    for (const auto* costs : {&sequential, &pipelined}) {
        REQUIRE(costs->size() == frames.size());
        for (const FrameCost& cost : *costs) {
            CHECK(cost.render_s > 0);
            CHECK(cost.readback_s > 0);
            CHECK(cost.encode_s > 0);
            CHECK(cost.encode_wait_s >= 0);
        }
    }
    for (const FrameCost& cost : sequential)
        CHECK(cost.encode_wait_s == 0);
}
