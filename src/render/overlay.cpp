#include "render/overlay.hpp"

#include "render/palette.hpp"
#include "render/text.hpp"

#include <algorithm>
#include <cmath>
#include <embedded_shaders.hpp>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <utility>

namespace sph {

FlatPainter::FlatPainter()
    : program_(gl::link_program(shaders::overlay_vert, shaders::overlay_frag, "")),
      vao_(gl::VertexArray::generate()), buffer_(gl::Buffer::generate()) {
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 1, GL_FLOAT, GL_FALSE, sizeof(OverlayVertex),
                          reinterpret_cast<void*>(12));
    glBindVertexArray(0);
    glProgramUniform1i(program_.id(), glGetUniformLocation(program_.id(), "u_colour_map"), 0);
}

void FlatPainter::draw(const std::vector<OverlayVertex>& vertices, GLenum mode,
                       const glm::mat4& transform, const glm::vec4& colour) const {
    if (vertices.empty())
        return;
    glUseProgram(program_.id());
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(OverlayVertex)),
                 vertices.data(), GL_STREAM_DRAW);
    glUniformMatrix4fv(glGetUniformLocation(program_.id(), "u_transform"), 1, GL_FALSE,
                       glm::value_ptr(transform));
    glUniform4fv(glGetUniformLocation(program_.id(), "u_colour"), 1, glm::value_ptr(colour));
    glDrawArrays(mode, 0, GLsizei(vertices.size()));
}

Ticks round_ticks(double lo, double hi, int most) {
    Ticks t;
    if (hi < lo)
        std::swap(lo, hi);
    const double span = hi - lo;
    if (!(span > 0) || !std::isfinite(span)) {
        t.values = {lo};
        t.labels = {fmt::format("{:.4g}", lo)};
        return t;
    }
    // The smallest round step that leaves at most `most` ticks in the range.
    double step = 0;
    for (double power = std::pow(10.0, std::floor(std::log10(span / most))); step == 0; power *= 10)
        for (const double m : {1.0, 2.0, 5.0})
            if (step == 0 &&
                std::floor(hi / (m * power) + 1e-9) - std::ceil(lo / (m * power) - 1e-9) + 1 <=
                    most)
                step = m * power;
    const double first = std::ceil(lo / step - 1e-9), last = std::floor(hi / step + 1e-9);
    for (double k = first; k <= last; ++k)
        t.values.push_back(k * step == 0 ? 0.0 : k * step); // no "-0"
    // One precision for every tick: the step's decimals, or powers of ten
    // with the step's significant digits where fixed decimals would be long.
    const double largest = std::max(std::abs(lo), std::abs(hi));
    const int decimals = std::max(0, int(-std::floor(std::log10(step) + 1e-9)));
    const bool scientific = largest >= 1e6 || decimals > 4;
    const int digits = std::max(
        0, int(std::floor(std::log10(largest) + 1e-9) - std::floor(std::log10(step) + 1e-9)));
    for (const double v : t.values)
        t.labels.push_back(scientific ? fmt::format("{:.{}e}", v, digits)
                                      : fmt::format("{:.{}f}", v, decimals));
    return t;
}

std::string format_caption(const std::string& pattern, const Snapshot& frame) {
    std::string out;
    for (std::size_t k = 0; k < pattern.size();) {
        auto take = [&](std::string_view name) {
            if (pattern.compare(k, name.size(), name) != 0)
                return false;
            k += name.size();
            return true;
        };
        if (take("{time}"))
            out += fmt::format("{:.3f}", frame.time);
        else if (take("{frame}"))
            out += fmt::format("{}", frame.frame);
        else if (take("{steps}"))
            out += fmt::format("{}", frame.steps);
        else
            out += pattern[k++];
    }
    return out;
}

namespace {

// Text sizes follow the image's height: legible at 180 px, not shouting at
// 1080 (19 px at 720). A frame wider than 16:9 (a long tank, 1280x400)
// sizes its text as the 16:9 frame of its width would: its scene is short
// and wide, with room above and below, and by its height alone the text
// was 10 px on a 1280 px wide frame, too small to read beside the tank.
float body_size(int width, int height) {
    const float reference = std::max(float(height), float(width) * 9.f / 16.f);
    return std::max(9.f, std::round(0.026f * reference));
}

} // namespace

Overlay::Overlay(const RenderSettings& s)
    : height_(s.height), body_px_(body_size(s.width, s.height)),
      title_px_(std::round(1.3f * body_px_)), label_(s.label), title_(s.title), caption_(s.caption),
      range_(s.range), ticks_(round_ticks(s.range[0], s.range[1])), backdrop_(s),
      text_colour_(palette(s.background).text), line_colour_(palette(s.background).bar_lines) {
    const std::string font = find_font(s.font, font_warning_);
    std::string face_warning;
    body_ = std::make_unique<TextFace>(font, int(body_px_), face_warning,
                                       std::vector<std::string>{label_, caption_});
    title_face_ = std::make_unique<TextFace>(font, int(title_px_), face_warning,
                                             std::vector<std::string>{title_});
    if (!face_warning.empty())
        font_warning_ = face_warning;
    // Above the scene: one line for the title and the caption, and a gap.
    const TextFace& b = *body_;
    const float line =
        std::max(title_.empty() ? 0.f : title_face_->ascent() + title_face_->descent(),
                 caption_.empty() ? 0.f : b.ascent() + b.descent());
    room_.top = line > 0 ? line + 0.5 * body_px_ : 0;
    // On the right: a gap, the bar, its ticks and their values, and the
    // bar's title above it, whichever is wider.
    float values = 0;
    for (const std::string& label : ticks_.labels)
        values = std::max(values, b.width(label));
    const float gap = 0.9f * body_px_;
    const float bar = gap + 0.9f * body_px_ + 0.4f * body_px_ + 0.35f * body_px_ + values;
    room_.right = std::max(bar, gap + b.width(label_)) + 0.3f * body_px_;
}

float Overlay::BarPlace::y_of(double value, const std::array<double, 2>& range) const {
    const double t = (value - range[0]) / (range[1] - range[0]);
    return float(bottom + (top - bottom) * t);
}

Overlay::BarPlace Overlay::bar_place(const FrameLayout& l) const {
    // In the band on the right, below the bar's title; the end values,
    // centred on their ticks, stay inside the band.
    const TextFace& b = *body_;
    return {.x = float(l.right.x) + 0.9f * body_px_,
            .width = 0.9f * body_px_,
            .top = float(l.right.y) + b.ascent() + b.descent() + 0.3f * body_px_,
            .bottom = float(l.right.bottom()) - 0.5f * b.cap_height()};
}

void Overlay::draw(const FlatPainter& painter, const Snapshot& frame, const FrameLayout& layout) {
    glDisable(GL_DEPTH_TEST);
    // Pixels, y down.
    const glm::mat4 pixels =
        glm::ortho(0.f, float(layout.width), float(layout.height), 0.f, -1.f, 1.f);
    draw_backing(layout);
    draw_colour_bar(painter, pixels, layout);
    draw_text(frame, pixels, layout);
}

void Overlay::draw_backing(const FrameLayout& l) {
    // The backdrop over everything outside the scene's rectangle (and a
    // little room for the spheres on its edges): a 3D splash or a close
    // camera never runs under the bands' text.
    const float pad = 0.3f * body_px_;
    const float x0 = float(l.scene.x) - pad, y0 = float(l.scene.y) - pad;
    const float x1 = float(l.scene.right()) + pad, y1 = float(l.scene.bottom()) + pad;
    const float w = float(l.width), h = float(l.height);
    bands_.clear();
    auto rect = [&](float ax, float ay, float bx, float by) {
        if (bx > ax && by > ay)
            bands_.push_back({ax, ay, bx - ax, by - ay});
    };
    rect(0, 0, w, y0);
    rect(0, y1, w, h);
    rect(0, y0, x0, y1);
    rect(x1, y0, w, y1);
    backdrop_.draw(bands_);
    glDisable(GL_DEPTH_TEST);
}

void Overlay::draw_colour_bar(const FlatPainter& painter, const glm::mat4& pixels,
                              const FrameLayout& layout) {
    const BarPlace bar = bar_place(layout);
    // The map from its low end at the bottom to its high end at the top.
    const float x0 = bar.x, x1 = bar.x + bar.width;
    triangles_ = {{x0, bar.bottom, 0, 0}, {x1, bar.bottom, 0, 0}, {x1, bar.top, 0, 1},
                  {x0, bar.bottom, 0, 0}, {x1, bar.top, 0, 1},    {x0, bar.top, 0, 1}};
    painter.draw(triangles_, GL_TRIANGLES, pixels, {1, 1, 1, 1});
    // Its frame, and a tick on its right at each round value.
    lines_ = {{x0, bar.top, 0, -1},    {x1, bar.top, 0, -1},    {x1, bar.top, 0, -1},
              {x1, bar.bottom, 0, -1}, {x1, bar.bottom, 0, -1}, {x0, bar.bottom, 0, -1},
              {x0, bar.bottom, 0, -1}, {x0, bar.top, 0, -1}};
    for (const double value : ticks_.values) {
        const float y = std::round(bar.y_of(value, range_)) + 0.5f;
        lines_.push_back({x1, y, 0, -1});
        lines_.push_back({x1 + 0.4f * body_px_, y, 0, -1});
    }
    painter.draw(lines_, GL_LINES, pixels, line_colour_);
}

void Overlay::draw_text(const Snapshot& frame, const glm::mat4& pixels, const FrameLayout& l) {
    const BarPlace bar = bar_place(l);
    const TextFace& b = *body_;
    // The ticks' values, each centred on its tick, a gap after it.
    text_.clear();
    const float values_x = bar.x + bar.width + 0.4f * body_px_ + 0.35f * body_px_;
    for (std::size_t k = 0; k < ticks_.values.size(); ++k)
        b.append(ticks_.labels[k], values_x,
                 bar.y_of(ticks_.values[k], range_) + 0.5f * b.cap_height(), text_);
    // The bar's title above it, from the bar's left edge.
    b.append(label_, bar.x, float(l.right.y) + b.ascent(), text_);
    // The title on the left of the band above the scene, the caption on
    // its right (on its left when there is no title), on one baseline.
    const float baseline = float(l.top.y) + std::max(title_.empty() ? 0.f : title_face_->ascent(),
                                                     caption_.empty() ? 0.f : b.ascent());
    if (!caption_.empty()) {
        const std::string caption = format_caption(caption_, frame);
        const float x = title_.empty() ? float(l.top.x) : float(l.top.right()) - b.width(caption);
        b.append(caption, x, baseline, text_);
    }
    text_painter_.draw(text_, b, pixels, text_colour_);
    if (!title_.empty()) {
        text_.clear();
        title_face_->append(title_, float(l.top.x), baseline, text_);
        text_painter_.draw(text_, *title_face_, pixels, text_colour_);
    }
}

} // namespace sph
