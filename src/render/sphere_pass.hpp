#pragma once
// The particles' spheres on the GPU: a ParticleBatch copied into one
// instance buffer and drawn instanced, either as ray-cast impostors on a
// square or a triangle around each sphere's image (OutlineRule's groups), or
// as the seed's icosphere mesh. Lit and coloured through the colour map
// bound to texture unit 0.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/lighting.hpp"
#include "render/particle_batch.hpp"
#include "render/render_settings.hpp"

#include <array>
#include <cstddef>
#include <string_view>
#include <vector>

namespace sph {

// The outlines an impostor is drawn on, around the unit circle: a square (a
// strip of two triangles), and the equilateral triangle whose inscribed
// circle it is (30% more area, half the triangles).
enum class Outline { square, triangle };

class SpherePass {
  public:
    // `impostor_defines` go before the impostor's shaders (the render
    // benchmark's variants; the renderer passes none).
    explicit SpherePass(const RenderSettings& settings, std::string_view impostor_defines = {});

    // Copies the batch's groups into the instance buffer, one after another.
    void upload(const ParticleBatch& batch);
    // Draws the uploaded batch's square_group (every sphere, for meshes) and
    // triangle_group; other groups are left to the caller.
    void draw(const ParticleBatch& batch, const Camera& camera) const;
    // The same spheres' depth only, through `light` (the shadow map's pass).
    void draw_depth(const ParticleBatch& batch, const Camera& light) const;
    // Draws the same spheres into a rank's layer (depth_composite.hpp): the
    // impostors' colour and depth as draw() gives them, and each sample's
    // depth bits and group. Impostors only.
    void draw_layer(const ParticleBatch& batch, const Camera& camera) const;
    // The light the next draws use; by default lit as in 2D, no shadows.
    void set_lighting(const Lighting& lighting) { lighting_ = lighting; }

    // For drawing a group with another program (the benchmark's variants):
    // the group's first instance in the buffer, the uniforms every sphere
    // program takes, and the instanced outlines.
    std::size_t first(std::size_t group) const { return first_[group]; }
    void set_uniforms(GLuint program, const Camera& camera) const;
    void draw_outlines(Outline outline, std::size_t first, std::size_t count) const;
    void draw_with(GLuint program, const ParticleBatch& batch, const Camera& camera) const;
    GLuint instance_buffer() const { return instances_.id(); }

  private:
    void make_outlines();
    void make_mesh(int subdivisions);

    bool impostor_;
    float radius_;
    std::array<float, 2> range_;
    gl::Program program_;       // the impostor's or the mesh's
    gl::Program depth_program_; // the impostor's depth only; empty for meshes
    gl::Program layer_program_; // the impostor's for a rank's layer; empty for meshes
    Lighting lighting_;
    gl::Buffer instances_;
    std::size_t capacity_ = 0; // instances the buffer holds
    std::vector<std::size_t> first_;
    std::array<gl::VertexArray, 2> outline_vaos_; // by Outline
    std::array<gl::Buffer, 2> outline_buffers_;
    gl::VertexArray mesh_vao_;
    gl::Buffer mesh_vertices_, mesh_indices_;
    GLsizei mesh_index_count_ = 0;
};

// Points the bound vertex array's attributes 1 (centre) and 2 (scalar) at
// `buffer`'s instances; divisor 1: one instance per sphere, 0: one vertex.
void bind_instance_attributes(GLuint buffer, GLuint divisor);

} // namespace sph
