#pragma once
// Screen-space ambient occlusion (3D): the frame's depth, once everything
// opaque is drawn, darkens the creases between spheres, where the fluid
// meets the floor and the walls, and the hollows of a splash: the depth cue
// that tells a layer of spheres from a ball of them. Two passes over the
// image (shaders/ambient_occlusion*.frag.glsl): the occlusion into a
// texture, then the frame multiplied by it, filtered. It reads only depth,
// so whatever wrote depth before it (a surface mesh too) is occluded alike.

#include "render/camera.hpp"
#include "render/gl_resources.hpp"

namespace sph {

class AmbientOcclusion {
  public:
    // For frames of width x height px; occluders count within `reach` m.
    AmbientOcclusion(int width, int height, double reach);
    // Darkens what `target` holds; leaves it bound, the depth test on and
    // blending off.
    void apply(const gl::RenderTarget& target, const Camera& camera);

  private:
    int width_, height_;
    float reach_;
    gl::Program occlusion_program_, apply_program_;
    gl::VertexArray vao_;
    gl::Texture depth_, occlusion_;
    gl::Framebuffer depth_framebuffer_, occlusion_framebuffer_;
};

} // namespace sph
