#pragma once
// Draws one frame of particles into an image, in the current GL context:
// instanced lit spheres coloured through a colour map, the domain box and the
// obstacles, a colour bar with its range and unit, and a caption. It sees
// only the Snapshot, never the simulation. Its parts, one file each: the
// camera and layout (camera.hpp), the particle batch (particle_batch.hpp),
// the spheres on the GPU (sphere_pass.hpp), the solids (scenery.hpp), the
// overlay (overlay.hpp) and the GL objects' lifetime (gl_resources.hpp).

#include "output/image.hpp"
#include "render/camera.hpp"
#include "render/frame_parts.hpp"
#include "render/render_settings.hpp"
#include "sph/snapshot.hpp"

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace sph {

class FrameSurface;
class RankCompositing;

struct FrameTimings {
    double fill_seconds = 0;     // culling and filling the instances (part of draw_seconds)
    double draw_seconds = 0;     // submitting and finishing the draw
    double readback_seconds = 0; // resolving and reading the pixels
    // render.style = surface: reconstructing the surface and colouring its
    // vertices on the CPU (part of draw_seconds; none where the export
    // reconstructed this frame's surface first), and its vertex count.
    double surface_seconds = 0;
    std::size_t surface_vertices = 0;
    // Each part's time (frame_parts.hpp), when the renderer times its parts
    // (FrameRenderer::time_parts); zeros otherwise.
    FramePartSeconds part_seconds{};
};

class FrameRenderer {
  public:
    // Needs a current GL 4.5 context; throws std::runtime_error on GL errors.
    // render.style = surface: the frame's surface from `surface`, shared with
    // the surface export (made with the settings' field, spacing and surface
    // keys), else from a FrameSurface of its own.
    explicit FrameRenderer(const RenderSettings& settings,
                           std::shared_ptr<FrameSurface> surface = nullptr);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    // The frame's image; over MPI ranks with depth compositing, every rank
    // calls it with the same frame and only rank 0's image is the frame
    // (the others' is empty: 0 x 0).
    Image render(const Snapshot& frame);
    // Over MPI ranks: `ranks` decides, frame by frame, whether the frame is
    // composited by depth (depth_composite.hpp); null: drawn here whole.
    // The spheres style with impostors only.
    void share_over_ranks(RankCompositing* ranks);
    // Whether the last frame was composited by depth, and what that cost
    // rank 0: drawing its own layer, waiting for and uploading the others',
    // and writing them into the frame (s).
    bool last_composited() const { return composited_; }
    double last_composite_seconds() const { return composite_seconds_; }
    const FrameTimings& last_timings() const { return timings_; }
    // Wait for each part of the frame to finish before the next begins, and
    // time it (FrameTimings::part_seconds): the benchmarks' breakdown. The
    // frame's pixels are the same; it takes a little longer.
    void time_parts(bool on) { time_parts_ = on; }
    // Particles drawn in the last frame (buried ones are skipped), and those
    // skipped as outside the view.
    std::size_t last_drawn() const;
    std::size_t last_outside_view() const;
    // Drawn particles of the last frame below and above the colour range.
    std::size_t last_below_range() const;
    std::size_t last_above_range() const;
    const RenderSettings& settings() const { return settings_; }
    // The camera of the last frame (render/camera.hpp).
    const CameraPose& last_pose() const;
    // The scene rectangle's width / height, the same every frame.
    double scene_aspect() const;
    // Why the overlay's text is not in the font asked for (empty: it is).
    const std::string& font_warning() const;

  private:
    Image render_composited(const Snapshot& frame);
    // The parts both ways of drawing a frame share: the backdrop and the
    // floor before the fluid; the solids, their creases, the glass, the
    // lines and the overlay after it, and the pixels read back.
    void draw_behind_fluid(const Camera& camera, PartClock& parts);
    Image draw_after_fluid(const Camera& camera, const Snapshot& frame,
                           std::chrono::steady_clock::time_point start, PartClock& parts);

    struct Parts;
    RenderSettings settings_;
    std::unique_ptr<Parts> parts_;
    FrameTimings timings_;
    bool time_parts_ = false;
    RankCompositing* ranks_ = nullptr;
    bool composited_ = false;
    double composite_seconds_ = 0;
    // Over ranks, the counts of every rank's particles (drawn, outside the
    // view, below and above the range), summed on rank 0.
    std::array<std::uint64_t, 4> counts_{};
};

} // namespace sph
