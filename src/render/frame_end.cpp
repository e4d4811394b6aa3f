#include "render/frame_end.hpp"

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/overlay.hpp"
#include "render/scenery.hpp"
#include "sph/wall_clock.hpp"

namespace sph {

Image finish_frame(Scenery& scenery, Overlay& overlay, FlatPainter& painter,
                   gl::RenderTarget& target, const Camera& camera, const Snapshot& frame,
                   const FrameLayout& layout, Clock::time_point start, FrameTimings& timings) {
    scenery.draw(painter, camera, frame.time);
    overlay.draw(painter, frame, layout);
    glFinish();
    timings.draw_seconds = seconds_since(start);

    const auto readback_start = Clock::now();
    Image image = target.read();
    gl::check_gl("frame rendering");
    timings.readback_seconds = seconds_since(readback_start);
    return image;
}

} // namespace sph
