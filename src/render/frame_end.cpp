#include "render/frame_end.hpp"

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/overlay.hpp"
#include "render/scenery.hpp"
#include "sph/wall_clock.hpp"

namespace sph {

void PartClock::mark(FramePart part) {
    if (!finish_)
        return;
    glFinish();
    const auto now = Clock::now();
    seconds_[std::size_t(part)] += std::chrono::duration<double>(now - last_).count();
    last_ = now;
}

Image finish_frame(Scenery& scenery, Overlay& overlay, FlatPainter& painter,
                   gl::RenderTarget& target, const Camera& camera, const Snapshot& frame,
                   const FrameLayout& layout, Clock::time_point start, FrameTimings& timings,
                   PartClock& parts) {
    // The glass over the fluid and the solids, then the lines.
    scenery.draw_glass(camera);
    parts.mark(FramePart::glass);
    scenery.draw(painter, camera, frame.time);
    parts.mark(FramePart::outlines);
    overlay.draw(painter, frame, layout);
    glFinish();
    parts.mark(FramePart::overlay);
    timings.draw_seconds = seconds_since(start);

    const auto readback_start = Clock::now();
    Image image = target.read();
    gl::check_gl("frame rendering");
    timings.readback_seconds = seconds_since(readback_start);
    parts.mark(FramePart::readback);
    return image;
}

} // namespace sph
