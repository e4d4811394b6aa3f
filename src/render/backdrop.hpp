#pragma once
// The backdrop behind the scene and the overlay: the palette's vertical
// gradient (render.background), drawn over the whole image before the scene
// and again under the overlay's bands, so the bands continue it.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/render_settings.hpp"

#include <vector>

namespace sph {

class Backdrop {
  public:
    explicit Backdrop(const RenderSettings& settings);
    // Over the whole viewport; no depth test, no depth written (the depth
    // test is on again afterwards).
    void draw() const;
    // Only inside `rects` (px, origin at the top left, y down).
    void draw(const std::vector<PixelRect>& rects) const;

  private:
    int height_;
    gl::Program program_;
    gl::VertexArray vao_; // none of its attributes: the triangle is from gl_VertexID
};

} // namespace sph
