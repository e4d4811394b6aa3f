#include "render/surface/frame_surface.hpp"

namespace sph {

FrameSurface::FrameSurface(ColourField field, double spacing, const SurfaceSettings& settings)
    : field_(field), spacing_(spacing), settings_(settings) {}

const Surface& FrameSurface::of(const Snapshot& frame) {
    const Key key{frame.frame, frame.steps};
    if (key_ != key) {
        // Forgotten first: a reconstruction that throws leaves no stale surface.
        key_.reset();
        surface_ = reconstruct_surface(frame, field_, spacing_, settings_);
        key_ = key;
        ++reconstructions_;
    }
    return surface_;
}

} // namespace sph
