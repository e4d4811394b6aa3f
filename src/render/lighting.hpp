#pragma once
// The light every lit program shares (shaders/lighting.glsl): a key light
// with its shadow map, and a sky/ground ambient, in the frame's view space.
// Built once a frame from the camera; a pass that shades (spheres, solids,
// the floor, a surface mesh) sets it on its program with set_lighting.

#include "render/camera.hpp"
#include "render/palette.hpp"

#include <glad/gl.h>
#include <glm/glm.hpp>
#include <string>

namespace sph {

// The texture unit the shadow map is bound to (the colour map is on 0).
inline constexpr GLint shadow_map_unit = 1;

struct Lighting {
    glm::vec3 to_light{0.35f, 0.6f, 0.7f}; // view space, unit: towards the key light
    glm::vec3 up{0, 1, 0};                 // view space, unit: against gravity
    glm::vec3 sky{0.3f}, ground{0.1f};     // linear ambient from above and below
    bool shadows = false;
    glm::mat4 shadow_from_view{1.f}; // view space to the shadow map's [0,1]^3
    float shadow_softness = 0;       // the filter's radius, shadow map uv
    float shadow_offset = 0;         // m, along the normal (acne)
};

// The key light for a 3D camera: from above (`up`, world space, against
// gravity), over the viewer's left shoulder and a little in front, so the
// fluid's lit side faces the camera and its shadow falls on the floor to the
// right and behind it. A 2D camera keeps the light fixed to the view.
Lighting key_light(const Camera& camera, const glm::dvec3& up, const Palette& palette);

// The shared lighting code (shaders/lighting.glsl) for a lit program, with
// the shadow map's lookup compiled in only where the frame has one
// (casts_shadows): without it the lookup is skipped, not merely switched off.
std::string lighting_source(bool shadows);

// Sets `lighting`'s uniforms on `program` (which is in use).
void set_lighting(GLuint program, const Lighting& lighting);

} // namespace sph
