#include "render/surface/surface_pass.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace sph {

namespace {

constexpr std::size_t vertex_floats = 7; // x, y, z, normal, scalar
// The 2D outline's width.
constexpr double outline_px = 2.0;

} // namespace

SurfacePass::SurfacePass(const RenderSettings& s)
    : range_{float(s.range[0]), float(s.range[1])},
      // The solids' vertex shader, with the colour field per vertex.
      program_(gl::link_program(shaders::solid_vert, shaders::surface_frag,
                                "#define VERTEX_SCALAR\n" + std::string(shaders::lighting))),
      vao_(gl::VertexArray::generate()), vertices_(gl::Buffer::generate()),
      indices_(gl::Buffer::generate()), flat_(s.dimension == 2) {
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
    constexpr GLsizei stride = vertex_floats * sizeof(float);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(12));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(24));
    glBindVertexArray(0);
}

void SurfacePass::upload(const SurfaceMesh& mesh, const Camera& camera) {
    const std::size_t nv = mesh.vertices();
    scratch_.resize(nv * vertex_floats);
    for (std::size_t v = 0; v < nv; ++v) {
        float* out = scratch_.data() + v * vertex_floats;
        for (int a = 0; a < 3; ++a) {
            out[a] = float(double(mesh.positions[3 * v + a]) - camera.origin[a]);
            out[3 + a] = mesh.normals[3 * v + a];
        }
        out[6] = mesh.scalar[v];
    }
    scratch_i_.assign(mesh.triangles.begin(), mesh.triangles.end());
    fill_indices_ = scratch_i_.size();
    // The outline: a quad along each segment, outline_px wide on screen
    // (orthographic: 1 m is pixels_per_radius() / 2 px), its ends pushed out
    // by half the width so that segments meet without gaps.
    outline_indices_ = 0;
    if (flat_ && !mesh.outline.empty()) {
        const double half = 0.5 * outline_px / (0.5 * camera.pixels_per_radius());
        for (std::size_t s = 0; s + 1 < mesh.outline.size(); s += 2) {
            // Copies: the insertions below may move scratch_.
            std::array<float, vertex_floats> a{}, b{};
            std::copy_n(scratch_.data() + mesh.outline[s] * vertex_floats, vertex_floats, a.data());
            std::copy_n(scratch_.data() + mesh.outline[s + 1] * vertex_floats, vertex_floats,
                        b.data());
            const double dx = double(b[0]) - a[0], dy = double(b[1]) - a[1];
            const double length = std::hypot(dx, dy);
            if (!(length > 0))
                continue;
            const double ux = dx / length * half, uy = dy / length * half;
            const std::uint32_t first = std::uint32_t(scratch_.size() / vertex_floats);
            const std::array<float, vertex_floats>* ends[2] = {&a, &b};
            for (int e = 0; e < 2; ++e)
                for (int side : {-1, 1}) {
                    const double along = e == 0 ? -1 : 1;
                    const std::array<float, vertex_floats>& p = *ends[e];
                    const float scalar = p[6];
                    scratch_.insert(scratch_.end(), {float(p[0] + along * ux - side * uy),
                                                     float(p[1] + along * uy + side * ux), p[2],
                                                     0.f, 0.f, 1.f, scalar});
                }
            scratch_i_.insert(scratch_i_.end(),
                              {first, first + 1, first + 2, first + 1, first + 3, first + 2});
        }
        outline_indices_ = scratch_i_.size() - fill_indices_;
    }
    glBindBuffer(GL_ARRAY_BUFFER, vertices_.id());
    if (scratch_.size() > vertex_capacity_) {
        vertex_capacity_ = scratch_.size() + scratch_.size() / 4;
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertex_capacity_ * sizeof(float)), nullptr,
                     GL_STREAM_DRAW);
    }
    if (!scratch_.empty())
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(scratch_.size() * sizeof(float)),
                        scratch_.data());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indices_.id());
    if (scratch_i_.size() > index_capacity_) {
        index_capacity_ = scratch_i_.size() + scratch_i_.size() / 4;
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(index_capacity_ * sizeof(std::uint32_t)),
                     nullptr, GL_STREAM_DRAW);
    }
    if (!scratch_i_.empty())
        glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0,
                        GLsizeiptr(scratch_i_.size() * sizeof(std::uint32_t)), scratch_i_.data());
}

void SurfacePass::set_camera(const Camera& camera) const {
    const GLuint p = program_.id();
    glUseProgram(p);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_view"), 1, GL_FALSE, glm::value_ptr(camera.view));
    glUniformMatrix4fv(glGetUniformLocation(p, "u_projection"), 1, GL_FALSE,
                       glm::value_ptr(camera.projection));
    glUniform1i(glGetUniformLocation(p, "u_orthographic"), camera.orthographic);
}

void SurfacePass::draw_depth(const Camera& light) const {
    if (fill_indices_ == 0 || flat_)
        return;
    // The shading program, its colour output unused: the shadow map's
    // framebuffer has depth only, and the surface's shader samples no map.
    set_camera(light);
    glBindVertexArray(vao_.id());
    glDrawElements(GL_TRIANGLES, GLsizei(fill_indices_), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

void SurfacePass::draw(const Camera& camera) const {
    if (fill_indices_ == 0)
        return;
    set_camera(camera);
    const GLuint p = program_.id();
    glUniform1i(glGetUniformLocation(p, "u_flat"), flat_);
    glUniform1i(glGetUniformLocation(p, "u_colour_map"), 0);
    glUniform2f(glGetUniformLocation(p, "u_range"), range_[0], range_[1]);
    glUniform1f(glGetUniformLocation(p, "u_lighten"), 0.f);
    glBindVertexArray(vao_.id());
    // 2D: one plane, painted in order (fill, then outline); the solids drawn
    // after cover it, as they cover the spheres.
    if (flat_)
        glDisable(GL_DEPTH_TEST);
    glDrawElements(GL_TRIANGLES, GLsizei(fill_indices_), GL_UNSIGNED_INT, nullptr);
    if (outline_indices_ > 0) {
        glUniform1f(glGetUniformLocation(p, "u_lighten"), 0.45f);
        glDrawElements(GL_TRIANGLES, GLsizei(outline_indices_), GL_UNSIGNED_INT,
                       reinterpret_cast<void*>(fill_indices_ * sizeof(std::uint32_t)));
    }
    if (flat_)
        glEnable(GL_DEPTH_TEST);
    glBindVertexArray(0);
}

} // namespace sph
