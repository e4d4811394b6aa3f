#pragma once
// The key light's shadow map (3D): the depth of everything that casts a
// shadow, as the key light sees the scene along its direction, in an
// orthographic view that holds the domain's bounding sphere. Whatever draws
// geometry (the spheres, the mesh obstacles, a surface mesh) passes a
// callback that draws its depth through a Camera, as it draws for the eye;
// the lit programs then look the map up (shaders/lighting.glsl).

#include "render/camera.hpp"
#include "render/gl_resources.hpp"
#include "render/lighting.hpp"

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sph {

class ShadowMap {
  public:
    // A square depth map of `size` texels a side.
    explicit ShadowMap(int size);

    // Draws a caster's depth through `light` (orthographic, positions
    // relative to the eye camera's origin, as for the eye).
    using DrawDepth = std::function<void(const Camera& light)>;

    // Renders the casters' depth as the key light (lighting.to_light, in
    // `eye`'s view space) sees the sphere of radius `reach` around the scene
    // coordinates' origin (the domain's centre), and sets lighting's shadow
    // fields: the map's transform, a filter of `softness` metres, the
    // offsets against self-shadowing. Leaves its framebuffer bound.
    void render(const Camera& eye, double reach, double softness, Lighting& lighting,
                const std::vector<DrawDepth>& casters);
    // Over MPI ranks each draws the spheres it owns (depth_composite.hpp):
    // `combine` gets the map's depths (24 bits scaled to 32, as GL gives
    // them) and makes them every rank's minimum, which is the map of every
    // caster whatever the order drawn; the map takes them back.
    void combine(const std::function<void(std::span<std::uint32_t>)>& combine);
    // Binds the map to shadow_map_unit.
    void bind() const;
    int size() const { return size_; }

  private:
    int size_;
    gl::Texture depth_;
    gl::Framebuffer framebuffer_;
    std::vector<std::uint32_t> texels_; // combine()'s scratch
};

// The map's side for a scene of bounding radius `reach` whose spheres have
// radius `radius`: about three texels across a sphere's radius, so the soft
// filter sees each sphere, between 512 and 2048 texels (what the shadow costs
// on llvmpipe grows with the texels a sphere covers).
int shadow_map_size(double reach, double radius);

} // namespace sph
