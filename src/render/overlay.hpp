#pragma once
// The overlay: the colour bar with its ticks, values and title, and the
// caption (time and frame), drawn in pixels over the scene in the room the
// layout reserves for them. Also the painter of flat lines and triangles
// that the overlay and the scenery's outlines share.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/render_settings.hpp"
#include "sph/snapshot.hpp"

#include <array>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace sph {

// A vertex of a flat drawing: position and colour-map coordinate (< 0: the
// drawing's one colour).
struct OverlayVertex {
    float x, y, z, ramp;
};

// Draws lines or triangles with one transform (the camera's, or a pixel
// grid) in one colour, or through the colour map bound to texture unit 0.
class FlatPainter {
  public:
    FlatPainter();
    // Nothing for no vertices.
    void draw(const std::vector<OverlayVertex>& vertices, GLenum mode, const glm::mat4& transform,
              const glm::vec4& colour) const;

  private:
    gl::Program program_;
    gl::VertexArray vao_;
    gl::Buffer buffer_;
};

class Overlay {
  public:
    Overlay(const RenderSettings& settings, const FrameLayout& layout);
    // Over whatever is drawn: no depth test from here on.
    void draw(const FlatPainter& painter, const Snapshot& frame);

  private:
    // The colour bar's place, px: its left edge, width, top and bottom.
    struct BarPlace {
        float x, width, top, bottom;
        // The k-th of five ticks, from the bottom.
        float tick_y(int k) const { return bottom + (top - bottom) * float(k) / 4.f; }
    };
    BarPlace bar_place() const;
    void draw_colour_bar(const FlatPainter& painter, const glm::mat4& pixels, const BarPlace& bar);
    void draw_text(const FlatPainter& painter, const glm::mat4& pixels, const BarPlace& bar,
                   const Snapshot& frame);

    FrameLayout layout_;
    std::string label_;
    std::array<double, 2> range_;
    // Scratch reused from frame to frame.
    std::vector<OverlayVertex> lines_, triangles_;
    std::vector<float> text_;
};

} // namespace sph
