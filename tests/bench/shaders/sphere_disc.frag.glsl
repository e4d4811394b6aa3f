// The flat disc of sphere_disc.vert.glsl, shaded with the normal of a sphere
// seen from far away (orthographically), which a few pixels cannot tell from
// the ray-cast one.
#ifdef POINTS
flat in float v_scale;
#else
in vec2 v_disc;
#endif
flat in vec3 v_albedo;

out vec4 f_colour;

void main() {
#ifdef POINTS
    // Point-sprite coordinates run downwards.
    vec2 p = (2.0 * gl_PointCoord - 1.0) * vec2(1.0, -1.0) * v_scale;
#else
    vec2 p = v_disc;
#endif
    float rr = dot(p, p);
    if (rr > 1.0)
        discard;
    vec3 normal = vec3(p, sqrt(1.0 - rr));
    f_colour = vec4(shade(v_albedo, normal, vec3(0.0, 0.0, 1.0)), 1.0);
}
