// The seed's technique: one sphere mesh, instanced at every particle.
layout(location = 0) in vec3 a_vertex;  // on the unit sphere, also its normal
layout(location = 1) in vec3 a_centre;  // per instance, world space
layout(location = 2) in float a_scalar; // per instance

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;
uniform sampler1D u_colour_map;
uniform vec2 u_range;

out vec3 v_normal;   // view space
out vec3 v_position; // view space
flat out vec3 v_albedo; // linear

void main() {
    vec4 position = u_view * vec4(a_centre + u_radius * a_vertex, 1.0);
    v_position = position.xyz;
    v_normal = mat3(u_view) * a_vertex;
    v_albedo = srgb_to_linear(map_colour(u_colour_map, u_range, a_scalar));
    gl_Position = u_projection * position;
}
