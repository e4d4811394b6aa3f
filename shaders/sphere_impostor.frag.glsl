// Ray-cast the sphere behind the outline; write its true depth so spheres
// intersect correctly with each other and with meshes.
in vec3 v_point;
flat in vec3 v_centre;
flat in vec3 v_albedo;

uniform mat4 u_projection;
uniform float u_radius;
uniform bool u_orthographic;

#ifdef RANK_LAYER
// Depth compositing over MPI ranks (render/depth_composite.hpp): each sample
// also keeps the float its fragment wrote as depth, clamped to [0, 1] as
// the depth buffer clamps it (so below 2^30 as bits, and no sign), and the
// group it was drawn in (bit 30), so rank 0 can write the same depth again.
layout(location = 0) out vec4 f_colour;
layout(location = 1) out uint f_depth_bits;
uniform uint u_group_bit;
#else
out vec4 f_colour;
#endif
#ifdef CONSERVATIVE_DEPTH
// The quad lies at the sphere's front: a driver may test depth before shading.
layout(depth_greater) out float gl_FragDepth;
#endif

void main() {
    vec3 origin = u_orthographic ? vec3(v_point.xy, v_centre.z + 2.0 * u_radius) : vec3(0.0);
    vec3 direction = u_orthographic ? vec3(0.0, 0.0, -1.0) : normalize(v_point);
    vec3 offset = origin - v_centre;
    float b = dot(offset, direction);
    float c = dot(offset, offset) - u_radius * u_radius;
    float discriminant = b * b - c;
    if (discriminant < 0.0)
        discard;
    vec3 hit = origin + (-b - sqrt(discriminant)) * direction;
    vec3 normal = (hit - v_centre) / u_radius;
    vec4 clip = u_projection * vec4(hit, 1.0);
    float depth = 0.5 * clip.z / clip.w + 0.5;
    gl_FragDepth = depth;
#ifdef RANK_LAYER
    f_depth_bits = (floatBitsToUint(clamp(depth, 0.0, 1.0)) & 0x7fffffffu) | u_group_bit;
#endif
#ifdef DEPTH_ONLY
    // The shadow map's pass: depth is all it keeps.
    f_colour = vec4(1.0);
#else
    f_colour = vec4(shade(v_albedo, normal, -direction, hit, 1.0), 1.0);
#endif
}
