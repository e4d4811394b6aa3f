#pragma once
// The end of every frame once its spheres are drawn, shared by FrameRenderer
// and the render benchmark's variants (tests/bench/render_variants.cpp), so
// that what they measure ends as the product's frames do.

#include "output/image.hpp"
#include "render/frame_renderer.hpp"

#include <chrono>

namespace sph {

class Scenery;
class Overlay;
class FlatPainter;
struct Camera;
struct FrameLayout;
namespace gl {
class RenderTarget;
}

// Draws the rest of the scenery (the tank's glass, the domain box, the
// obstacles' outlines and the paddles; the mesh obstacles are drawn before,
// with the particles: Scenery::draw_solids), then the overlay (colour bar, its labels, the caption)
// over everything, and reads the samples back resolved, rows top-down. Sets the draw time (since
// `start`, which began the frame) and the readback time.
// `parts` times the glass, the outlines, the overlay and the readback.
Image finish_frame(Scenery& scenery, Overlay& overlay, FlatPainter& painter,
                   gl::RenderTarget& target, const Camera& camera, const Snapshot& frame,
                   const FrameLayout& layout, std::chrono::steady_clock::time_point start,
                   FrameTimings& timings, PartClock& parts);

} // namespace sph
