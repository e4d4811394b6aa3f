// Screen-space ambient occlusion from the frame's depth: at each pixel, the
// points of the depth buffer within `u_reach` around it that rise above its
// tangent plane hide part of its sky. The mean cosine of their elevation,
// with a falloff to zero at the reach, is the share occluded (an
// obscurance estimate after McGuire et al. 2011, "The Alchemy Screen-Space
// Ambient Obscurance Algorithm", eq. 7, in its unitless form). 12 samples on
// a spiral turned by a 4x4 interleaved pattern, which the apply pass's 4x4
// box filter removes.
in vec2 v_uv;

uniform sampler2D u_depth;
uniform mat4 u_inverse_projection;
uniform float u_reach;    // m
uniform float u_focal_px; // px per unit of x / z at the image's height
uniform float u_strength;

out vec4 f_occlusion;

vec3 view_at(ivec2 p, ivec2 size) {
    float d = texelFetch(u_depth, p, 0).r;
    vec2 uv = (vec2(p) + 0.5) / vec2(size);
    vec4 v = u_inverse_projection * vec4(2.0 * vec3(uv, d) - 1.0, 1.0);
    return v.xyz / v.w;
}

void main() {
    ivec2 size = textureSize(u_depth, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    if (texelFetch(u_depth, p, 0).r >= 1.0) {
        f_occlusion = vec4(1.0);
        return;
    }
    vec3 centre = view_at(p, size);
    // The normal from the nearer neighbour along each axis: across an
    // outline the farther one belongs to something else.
    vec3 right = view_at(min(p + ivec2(1, 0), size - 1), size) - centre;
    vec3 left = centre - view_at(max(p - ivec2(1, 0), ivec2(0)), size);
    vec3 up = view_at(min(p + ivec2(0, 1), size - 1), size) - centre;
    vec3 down = centre - view_at(max(p - ivec2(0, 1), ivec2(0)), size);
    vec3 dx = abs(right.z) < abs(left.z) ? right : left;
    vec3 dy = abs(up.z) < abs(down.z) ? up : down;
    vec3 normal = normalize(cross(dx, dy));
    if (dot(normal, centre) > 0.0)
        normal = -normal;

    float reach_px = clamp(u_reach * u_focal_px / max(-centre.z, 1e-6), 3.0, 64.0);
    int cell = (p.x & 3) + 4 * (p.y & 3);
    // A 4x4 Bayer order, so neighbouring pixels take far-apart turns.
    const int bayer[16] = int[](0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5);
    float turn = float(bayer[cell]) / 16.0 * 6.2831853;
    float occluded = 0.0;
    for (int k = 0; k < 12; ++k) {
        float angle = turn + float(k) * 2.3999632; // the golden angle
        float r = reach_px * sqrt((float(k) + 0.5) / 12.0);
        ivec2 q = clamp(p + ivec2(round(r * vec2(cos(angle), sin(angle)))), ivec2(0), size - 1);
        vec3 v = view_at(q, size) - centre;
        float vv = dot(v, v);
        float falloff = max(0.0, 1.0 - vv / (u_reach * u_reach));
        occluded += falloff * max(0.0, dot(v, normal) - 0.02 * u_reach) / sqrt(vv + 1e-12);
    }
    f_occlusion = vec4(clamp(1.0 - u_strength * occluded / 12.0, 0.0, 1.0));
}
