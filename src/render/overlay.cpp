#include "render/overlay.hpp"

#include "render/text.hpp"

#include <algorithm>
#include <embedded_shaders.hpp>
#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

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

Overlay::Overlay(const RenderSettings& settings, const FrameLayout& layout)
    : layout_(layout), label_(settings.label), range_(settings.range) {}

Overlay::BarPlace Overlay::bar_place() const {
    // In the room on the right, below the caption.
    const FrameLayout& l = layout_;
    const float scale = l.text_scale;
    return {.x = float(l.width - l.bar_space) + 8.f * scale,
            .width = 9.f * scale,
            .top = float(l.caption_space + l.margin) + 10.f * scale,
            .bottom = float(l.height - l.margin) - 5.f * scale};
}

void Overlay::draw(const FlatPainter& painter, const Snapshot& frame) {
    glDisable(GL_DEPTH_TEST);
    // Pixels, y down.
    const glm::mat4 pixels =
        glm::ortho(0.f, float(layout_.width), float(layout_.height), 0.f, -1.f, 1.f);
    const BarPlace bar = bar_place();
    draw_colour_bar(painter, pixels, bar);
    draw_text(painter, pixels, bar, frame);
}

void Overlay::draw_colour_bar(const FlatPainter& painter, const glm::mat4& pixels,
                              const BarPlace& bar) {
    // The map from its low end at the bottom to its high end at the top.
    const float x0 = bar.x, x1 = bar.x + bar.width;
    triangles_ = {{x0, bar.bottom, 0, 0}, {x1, bar.bottom, 0, 0}, {x1, bar.top, 0, 1},
                  {x0, bar.bottom, 0, 0}, {x1, bar.top, 0, 1},    {x0, bar.top, 0, 1}};
    painter.draw(triangles_, GL_TRIANGLES, pixels, {1, 1, 1, 1});
    // Its frame and five ticks on its right.
    lines_ = {{x0, bar.top, 0, -1},    {x1, bar.top, 0, -1},    {x1, bar.top, 0, -1},
              {x1, bar.bottom, 0, -1}, {x1, bar.bottom, 0, -1}, {x0, bar.bottom, 0, -1},
              {x0, bar.bottom, 0, -1}, {x0, bar.top, 0, -1}};
    for (int k = 0; k <= 4; ++k) {
        const float y = bar.tick_y(k);
        lines_.push_back({x1, y, 0, -1});
        lines_.push_back({x1 + 2.5f * layout_.text_scale, y, 0, -1});
    }
    painter.draw(lines_, GL_LINES, pixels, {0.85f, 0.86f, 0.88f, 1.f});
}

void Overlay::draw_text(const FlatPainter& painter, const glm::mat4& pixels, const BarPlace& bar,
                        const Snapshot& frame) {
    const FrameLayout& l = layout_;
    const float scale = l.text_scale, glyph_h = 7.f * scale;
    text_.clear();
    // The ticks' values, the bar's title above it (kept inside the image),
    // and the caption in the room on top.
    for (int k = 0; k <= 4; ++k) {
        const double value = range_[0] + (range_[1] - range_[0]) * k / 4.0;
        append_text_triangles(fmt::format("{:.4g}", value), bar.x + bar.width + 4.5f * scale,
                              bar.tick_y(k) - 0.5f * glyph_h, scale, text_);
    }
    const float label_w = text_width(label_, scale);
    append_text_triangles(label_, std::min(bar.x, float(l.width) - label_w - 4.f * scale),
                          bar.top - 2.5f * glyph_h, scale, text_);
    append_text_triangles(fmt::format("t = {:.3f} s    frame {}", frame.time, frame.frame),
                          float(l.margin), float(l.margin) * 0.5f + 2.f * scale, scale, text_);
    triangles_.clear();
    for (std::size_t k = 0; k + 1 < text_.size(); k += 2)
        triangles_.push_back({text_[k], text_[k + 1], 0, -1});
    painter.draw(triangles_, GL_TRIANGLES, pixels, {0.9f, 0.91f, 0.93f, 1.f});
}

} // namespace sph
