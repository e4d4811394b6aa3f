// Sphere impostor: one camera-facing outline per particle (instanced), a
// triangle or a square around the sphere's exact silhouette (the unit circle
// in corner coordinates); the fragment shader ray-casts the sphere.
layout(location = 0) in vec2 a_corner;  // outline corner, around the unit circle
layout(location = 1) in vec3 a_centre;  // per instance, world space
layout(location = 2) in float a_scalar; // per instance, the coloured field

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;
uniform bool u_orthographic;
uniform sampler1D u_colour_map;
uniform vec2 u_range;

out vec3 v_point;        // view-space point on the quad
flat out vec3 v_centre;  // view-space sphere centre
flat out vec3 v_albedo; // linear

void main() {
    vec3 centre = (u_view * vec4(a_centre, 1.0)).xyz;
    // How far in front of the centre the outline lies: at the front, every
    // ray-cast depth lies behind the outline's (conservative depth, a
    // variant the render benchmark measures: tests/bench/render_variants.hpp).
#ifdef CONSERVATIVE_DEPTH
    float front = u_radius;
#else
    float front = 0.0;
#endif
    Outline o = sphere_outline(centre, u_radius, front, u_orthographic);
    v_point = centre + front * o.to_eye +
              o.half_size * (a_corner.x * o.axis_x + a_corner.y * o.axis_y);
    v_centre = centre;
    v_albedo = srgb_to_linear(map_colour(u_colour_map, u_range, a_scalar));
    gl_Position = u_projection * vec4(v_point, 1.0);
}
