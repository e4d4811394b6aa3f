#pragma once
// The fluid's surface on the GPU (render.style = surface): a SurfaceMesh
// uploaded per frame and drawn in the frame's context, coloured through the
// colour map bound to texture unit 0 (shaders/surface.*.glsl). 3D: lit with
// a Fresnel reflection, depth-tested with the solids. 2D: the region filled
// flat and its outline drawn over it, 2 px wide, a lighter shade.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/render_settings.hpp"
#include "render/surface/surface_mesh.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace sph {

class SurfacePass {
  public:
    explicit SurfacePass(const RenderSettings& settings);
    // Copies the mesh (positions made relative to the camera's origin) and,
    // in 2D, the outline's quads, whose width depends on the camera's scale.
    void upload(const SurfaceMesh& mesh, const Camera& camera);
    void draw(const Camera& camera) const;
    // 3D: the mesh's depth through the key light's camera, for the shadow
    // map (ShadowMap::DrawDepth), so the surface casts its shadow on the
    // floor and the solids as the spheres do.
    void draw_depth(const Camera& light) const;

  private:
    void set_camera(const Camera& camera) const;

    std::array<float, 2> range_;
    gl::Program program_;
    gl::VertexArray vao_;
    gl::Buffer vertices_, indices_;
    std::size_t vertex_capacity_ = 0, index_capacity_ = 0; // floats, indices
    std::size_t fill_indices_ = 0, outline_indices_ = 0;   // drawn, after one another
    bool flat_ = false;
    std::vector<float> scratch_;           // interleaved vertices
    std::vector<std::uint32_t> scratch_i_; // indices
};

} // namespace sph
