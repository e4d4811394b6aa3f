#include "render/sphere_pass.hpp"

#include "render/depth_composite.hpp"
#include "render/sphere_geometry.hpp"

#include <cmath>
#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

namespace sph {

namespace {

constexpr GLsizeiptr instance_bytes = 16; // x, y, z, scalar

} // namespace

void bind_instance_attributes(GLuint buffer, GLuint divisor) {
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, instance_bytes, nullptr);
    glVertexAttribDivisor(1, divisor);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 1, GL_FLOAT, GL_FALSE, instance_bytes, reinterpret_cast<void*>(12));
    glVertexAttribDivisor(2, divisor);
}

SpherePass::SpherePass(const RenderSettings& s, std::string_view impostor_defines)
    : impostor_(s.spheres == SphereDrawing::impostor),
      radius_(float(s.radius)), range_{float(s.range[0]), float(s.range[1])},
      instances_(gl::Buffer::generate()) {
    const std::string lighting = lighting_source(casts_shadows(s));
    if (impostor_) {
        program_ = gl::link_program(shaders::sphere_impostor_vert, shaders::sphere_impostor_frag,
                                    std::string(impostor_defines) + lighting);
        depth_program_ =
            gl::link_program(shaders::sphere_impostor_vert, shaders::sphere_impostor_frag,
                             "#define DEPTH_ONLY\n" + std::string(impostor_defines) + lighting);
        layer_program_ =
            gl::link_program(shaders::sphere_impostor_vert, shaders::sphere_impostor_frag,
                             "#define RANK_LAYER\n" + std::string(impostor_defines) + lighting);
        make_outlines();
    } else {
        program_ = gl::link_program(shaders::sphere_mesh_vert, shaders::sphere_mesh_frag, lighting);
        make_mesh(s.mesh_subdivisions);
    }
    glBindVertexArray(0);
}

void SpherePass::make_outlines() {
    const float sqrt3 = std::sqrt(3.f);
    const std::array<std::vector<float>, 2> corners = {
        std::vector<float>{-1, -1, 1, -1, -1, 1, 1, 1}, // a strip
        std::vector<float>{0, 2, -sqrt3, -1, sqrt3, -1}};
    for (std::size_t k = 0; k < 2; ++k) {
        outline_vaos_[k] = gl::VertexArray::generate();
        glBindVertexArray(outline_vaos_[k].id());
        outline_buffers_[k] = gl::Buffer::generate();
        glBindBuffer(GL_ARRAY_BUFFER, outline_buffers_[k].id());
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(corners[k].size() * sizeof(float)),
                     corners[k].data(), GL_STATIC_DRAW);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
        bind_instance_attributes(instances_.id(), 1);
    }
}

void SpherePass::make_mesh(int subdivisions) {
    const SphereMesh mesh = make_icosphere(subdivisions);
    mesh_vao_ = gl::VertexArray::generate();
    glBindVertexArray(mesh_vao_.id());
    mesh_vertices_ = gl::Buffer::generate();
    glBindBuffer(GL_ARRAY_BUFFER, mesh_vertices_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(mesh.vertices.size() * sizeof mesh.vertices[0]),
                 mesh.vertices.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    mesh_indices_ = gl::Buffer::generate();
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh_indices_.id());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    mesh_index_count_ = GLsizei(mesh.indices.size());
    bind_instance_attributes(instances_.id(), 1);
}

void SpherePass::upload(const ParticleBatch& batch) {
    first_.assign(batch.groups(), 0);
    const std::size_t drawn = batch.drawn();
    if (drawn == 0)
        return;
    glBindBuffer(GL_ARRAY_BUFFER, instances_.id());
    if (drawn > capacity_) {
        capacity_ = drawn + drawn / 4;
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(capacity_) * instance_bytes, nullptr,
                     GL_STREAM_DRAW);
    }
    for (std::size_t group = 0; group < batch.groups(); ++group) {
        first_[group] = group == 0 ? 0 : first_[group - 1] + batch.count(group - 1);
        glBufferSubData(GL_ARRAY_BUFFER, GLintptr(first_[group]) * instance_bytes,
                        GLsizeiptr(batch.count(group)) * instance_bytes,
                        batch.instances(group).data());
    }
}

void SpherePass::set_uniforms(GLuint program, const Camera& camera) const {
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_view"), 1, GL_FALSE,
                       glm::value_ptr(camera.view));
    glUniformMatrix4fv(glGetUniformLocation(program, "u_projection"), 1, GL_FALSE,
                       glm::value_ptr(camera.projection));
    glUniform1f(glGetUniformLocation(program, "u_radius"), radius_);
    glUniform1i(glGetUniformLocation(program, "u_orthographic"), camera.orthographic);
    glUniform1i(glGetUniformLocation(program, "u_colour_map"), 0);
    glUniform2f(glGetUniformLocation(program, "u_range"), range_[0], range_[1]);
    sph::set_lighting(program, lighting_);
}

void SpherePass::draw_outlines(Outline outline, std::size_t first, std::size_t count) const {
    if (count == 0)
        return;
    glBindVertexArray(outline_vaos_[std::size_t(outline)].id());
    if (outline == Outline::square)
        glDrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, 4, GLsizei(count), GLuint(first));
    else
        glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, GLsizei(count), GLuint(first));
}

void SpherePass::draw(const ParticleBatch& batch, const Camera& camera) const {
    draw_with(program_.id(), batch, camera);
}

void SpherePass::draw_depth(const ParticleBatch& batch, const Camera& light) const {
    draw_with(impostor_ ? depth_program_.id() : program_.id(), batch, light);
}

void SpherePass::draw_layer(const ParticleBatch& batch, const Camera& camera) const {
    draw_with(layer_program_.id(), batch, camera);
}

void SpherePass::draw_with(GLuint program, const ParticleBatch& batch, const Camera& camera) const {
    if (batch.drawn() == 0)
        return;
    set_uniforms(program, camera);
    if (!impostor_) {
        glBindVertexArray(mesh_vao_.id());
        glDrawElementsInstanced(GL_TRIANGLES, mesh_index_count_, GL_UNSIGNED_INT, nullptr,
                                GLsizei(batch.count(square_group)));
        return;
    }
    // A rank's layer marks the spheres drawn on triangles (depth_composite.hpp);
    // other programs have no such uniform, and location -1 sets nothing.
    const GLint group_bit = glGetUniformLocation(program, "u_group_bit");
    glUniform1ui(group_bit, 0u);
    draw_outlines(Outline::square, first(square_group), batch.count(square_group));
    glUniform1ui(group_bit, triangle_group_bit);
    if (batch.groups() > triangle_group)
        draw_outlines(Outline::triangle, first(triangle_group), batch.count(triangle_group));
}

} // namespace sph
