#pragma once
// A frame's parts in drawing order, and a clock that times each on its own
// (the render and surface benchmarks' breakdown). GL queues its work, and
// llvmpipe rasterises it when the queue is flushed, so a part is timed only
// if the frame waits for it (glFinish) before the next begins; that wait
// costs the overlap of one part's rasterising with the next's submission,
// so frames are timed this way only on request.

#include "sph/wall_clock.hpp"

#include <array>
#include <cstddef>
#include <string_view>

namespace sph {

enum class FramePart {
    fill,       // CPU: cull and classify the particles, fill the instances
    surface,    // CPU: render.style = surface, reconstruct and colour the mesh
    upload,     // the instances or the mesh to the GL
    shadow_map, // the key light's depth (render.shadows)
    backdrop,   // the gradient behind the scene
    floor,      // the shadow-catching floor (render.floor)
    fluid,      // the spheres or the surface mesh
    solids,     // mesh obstacles
    occlusion,  // screen-space ambient occlusion (render.ambient_occlusion)
    glass,      // the tank's walls (render.tank)
    outlines,   // the domain box's edges, obstacles, paddles
    overlay,    // the bands, the colour bar and the text
    readback,   // resolving the samples and reading the pixels back
};
inline constexpr std::size_t frame_part_count = std::size_t(FramePart::readback) + 1;

inline constexpr std::string_view frame_part_name(FramePart part) {
    constexpr std::array<std::string_view, frame_part_count> names = {
        "fill",   "surface",   "upload", "shadow_map", "backdrop", "floor",   "fluid",
        "solids", "occlusion", "glass",  "outlines",   "overlay",  "readback"};
    return names[std::size_t(part)];
}

using FramePartSeconds = std::array<double, frame_part_count>;

// Times the parts of one frame: mark(part) after each part ends adds the time
// since the previous mark to it; with `finish` it first waits for the GL to
// finish the part's drawing. Without it, marks cost nothing and record
// nothing.
class PartClock {
  public:
    PartClock(bool finish, FramePartSeconds& seconds) : finish_(finish), seconds_(seconds) {
        seconds_.fill(0);
        last_ = Clock::now();
    }
    void mark(FramePart part);

  private:
    bool finish_;
    FramePartSeconds& seconds_;
    Clock::time_point last_;
};

} // namespace sph
