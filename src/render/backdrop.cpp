#include "render/backdrop.hpp"

#include "render/palette.hpp"

#include <cmath>
#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sph {

Backdrop::Backdrop(const RenderSettings& s)
    : height_(s.height),
      program_(gl::link_program(shaders::fullscreen_vert, shaders::backdrop_frag, "")),
      vao_(gl::VertexArray::generate()) {
    const Palette& p = palette(s.background);
    const GLuint id = program_.id();
    glProgramUniform3fv(id, glGetUniformLocation(id, "u_top"), 1, glm::value_ptr(p.backdrop_top));
    glProgramUniform3fv(id, glGetUniformLocation(id, "u_bottom"), 1,
                        glm::value_ptr(p.backdrop_bottom));
    glProgramUniform1f(id, glGetUniformLocation(id, "u_image_height"), float(s.height));
}

void Backdrop::draw() const {
    glDisable(GL_DEPTH_TEST);
    glUseProgram(program_.id());
    glBindVertexArray(vao_.id());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
}

void Backdrop::draw(const std::vector<PixelRect>& rects) const {
    glEnable(GL_SCISSOR_TEST);
    for (const PixelRect& r : rects) {
        // The pixels whose centres are inside, as a triangle would cover;
        // GL's rows run bottom-up.
        const int x0 = int(std::ceil(r.x - 0.5)), x1 = int(std::ceil(r.right() - 0.5));
        const int y0 = int(std::ceil(r.y - 0.5)), y1 = int(std::ceil(r.bottom() - 0.5));
        if (x1 <= x0 || y1 <= y0)
            continue;
        glScissor(x0, height_ - y1, x1 - x0, y1 - y0);
        draw();
    }
    glDisable(GL_SCISSOR_TEST);
}

} // namespace sph
