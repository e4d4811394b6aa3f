#pragma once
// The overlay: the colour bar with its ticks, values and title, a title line
// and the caption, each in a band the layout reserves beside the scene
// (OverlayRoom), on a backing of the backdrop so nothing of the scene
// runs under the text. Also the painter of flat lines and triangles that the
// overlay and the scenery's outlines share.

#include "render/backdrop.hpp"
#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/render_settings.hpp"
#include "render/text.hpp"
#include "sph/snapshot.hpp"

#include <array>
#include <glm/glm.hpp>
#include <memory>
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

// Colour-bar ticks: values at round steps (1, 2 or 5 times a power of ten)
// within [lo, hi], at most `most` of them and at least 2 where the range
// allows, each written with the same number of decimals.
struct Ticks {
    std::vector<double> values;
    std::vector<std::string> labels;
};
Ticks round_ticks(double lo, double hi, int most = 6);

// The caption's text for `frame`: `pattern` with {time} (s, 3 decimals),
// {frame} and {steps} replaced; anything else is kept as written.
std::string format_caption(const std::string& pattern, const Snapshot& frame);

class Overlay {
  public:
    // Measures the text at the image's size (needs the GL context: the
    // glyph atlases are textures).
    explicit Overlay(const RenderSettings& settings);
    // The room it asks for beside the scene.
    OverlayRoom room() const { return room_; }
    // Why the font was not the one asked for (empty: it was).
    const std::string& font_warning() const { return font_warning_; }
    bool font_from_file() const { return body_->from_font(); }
    // The backdrop its bands are backed with, which the frame starts from.
    const Backdrop& backdrop() const { return backdrop_; }

    // Over whatever is drawn, in the layout's bands: no depth test from here on.
    void draw(const FlatPainter& painter, const Snapshot& frame, const FrameLayout& layout);

  private:
    void draw_backing(const FrameLayout& layout);
    void draw_colour_bar(const FlatPainter& painter, const glm::mat4& pixels,
                         const FrameLayout& layout);
    void draw_text(const Snapshot& frame, const glm::mat4& pixels, const FrameLayout& layout);

    // The bar's place in the right band, px.
    struct BarPlace {
        float x, width, top, bottom;
        float y_of(double value, const std::array<double, 2>& range) const;
    };
    BarPlace bar_place(const FrameLayout& layout) const;

    int height_;
    float body_px_, title_px_;
    std::string label_, title_, caption_;
    std::array<double, 2> range_;
    Ticks ticks_;
    std::string font_warning_;
    std::unique_ptr<TextFace> body_, title_face_;
    TextPainter text_painter_;
    Backdrop backdrop_;
    glm::vec4 text_colour_, line_colour_;
    OverlayRoom room_;
    // Scratch reused from frame to frame.
    std::vector<OverlayVertex> lines_, triangles_;
    std::vector<PixelRect> bands_;
    std::vector<TextVertex> text_;
};

} // namespace sph
