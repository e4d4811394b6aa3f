// Shared by every lit program (spheres, solids, the floor), so all are lit
// the same. Linear light: colours come in as sRGB values (the colour map,
// as the colour bar shows it), are decoded, lit, and encoded again, so a
// sphere's side facing the key light shows the bar's own colour and its
// shading falls off as light does. A key light (shadowed through the shadow
// map, render/lighting.hpp) and an ambient blended from a bright sky above
// to a dark ground below; on glossy surfaces a Blinn-Phong highlight and the
// sky reflected by Schlick's Fresnel term (water's F0 = 0.02, n = 1.33),
// which gives drops their wet rim.
uniform vec3 u_light; // view space, towards the key light
uniform vec3 u_up;    // view space, against gravity
uniform vec3 u_sky, u_ground;
uniform bool u_shadows;
uniform sampler2DShadow u_shadow_map;
uniform mat4 u_shadow_from_view;
uniform float u_shadow_softness; // uv, the filter's radius
uniform float u_shadow_offset;   // m, along the normal

vec3 srgb_to_linear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}
// The curve's 1.055 c^(1 / 2.4) - 0.055 from square roots, as c, c^(1/2),
// c^(1/4) and c^(1/8) weighted by a least-squares fit over [0.0031308, 1]:
// within 0.012 of an 8-bit level of the exact curve, at a fraction of the
// cost of llvmpipe's pow() (an exp2 of a log2, both polynomials), which
// every lit fragment paid three times.
vec3 linear_to_srgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    vec3 r2 = sqrt(c), r4 = sqrt(r2), r8 = sqrt(r4);
    vec3 curve = 0.64237120 * r2 + 0.71210517 * r4 - 0.33686796 * r8 - 0.01756558 * c;
    return mix(c * 12.92, curve, step(vec3(0.0031308), c));
}

// How much of the key light reaches `position` (view space): the shadow map
// compared at 12 points of a Poisson disc, each with the hardware's 2x2
// bilinear comparison, for a soft edge of about the filter's radius
// (percentage-closer filtering, Reeves, Salesin & Cook 1987). Looked up a
// little off the surface along its normal, so a surface does not shadow
// itself.
// Compiled in only where the frame has a shadow map (SHADOWS defined,
// lighting_source): llvmpipe runs both sides of a branch, a uniform one
// too, so a disabled lookup still cost its 12 texture reads a fragment.
float key_visibility(vec3 position, vec3 normal) {
#ifndef SHADOWS
    return 1.0;
#else
    if (!u_shadows)
        return 1.0;
    vec3 s = (u_shadow_from_view * vec4(position + u_shadow_offset * normal, 1.0)).xyz;
    if (any(lessThan(s, vec3(0.0))) || any(greaterThan(s, vec3(1.0))))
        return 1.0;
    const vec2 disc[12] = vec2[](vec2(-0.326, -0.406), vec2(-0.840, -0.074), vec2(-0.696, 0.457),
                                 vec2(-0.203, 0.621), vec2(0.962, -0.195), vec2(0.473, -0.480),
                                 vec2(0.519, 0.767), vec2(0.185, -0.893), vec2(0.507, 0.064),
                                 vec2(0.896, 0.412), vec2(-0.322, -0.933), vec2(-0.792, -0.598));
    float lit = 0.0;
    for (int k = 0; k < 12; ++k)
        lit += textureLod(u_shadow_map, vec3(s.xy + u_shadow_softness * disc[k], s.z), 0.0);
    return lit / 12.0;
#endif
}

// `albedo` linear (srgb_to_linear of the colour map's or a flat sRGB
// colour: a sphere's is decoded once per vertex, not per fragment);
// `normal`, `to_eye` unit, view space; `visible` the share of the key light
// that reaches the point; `gloss` 0 (matte) to 1 (the fluid's). Returns
// sRGB.
vec3 shade_lit(vec3 albedo, vec3 normal, vec3 to_eye, float visible, float gloss) {
    float key = max(dot(normal, u_light), 0.0) * visible;
    vec3 ambient = mix(u_ground, u_sky, 0.5 + 0.5 * dot(normal, u_up));
    // The key at 0.7: where it meets the surface head on, ambient plus key
    // is about 1, and the sphere shows the colour bar's colour.
    vec3 colour = albedo * (ambient + 0.7 * key);
    // The 80th power as products (x^64 x^16), exact where pow() is not.
    float h = max(dot(normal, normalize(u_light + to_eye)), 0.0);
    float h2 = h * h, h4 = h2 * h2, h8 = h4 * h4, h16 = h8 * h8, h64 = h16 * h16 * h16 * h16;
    float highlight = h64 * h16;
    // Clamped: dot() may pass 1 by a rounding. The fifth power as products:
    // llvmpipe's pow() is an exp2 of a log2, dearer and no more exact.
    float grazing = clamp(1.0 - dot(normal, to_eye), 0.0, 1.0);
    float grazing2 = grazing * grazing;
    float fresnel = 0.02 + 0.98 * grazing2 * grazing2 * grazing;
    colour = mix(colour, 1.6 * u_sky, 0.6 * gloss * fresnel) + gloss * 0.6 * highlight * key;
    return linear_to_srgb(colour);
}

// At `position` (view space), shadowed.
vec3 shade(vec3 albedo, vec3 normal, vec3 to_eye, vec3 position, float gloss) {
    float visible = dot(normal, u_light) > 0.0 ? key_visibility(position, normal) : 0.0;
    return shade_lit(albedo, normal, to_eye, visible, gloss);
}

// Unshadowed, glossy: the render benchmark's flat discs.
vec3 shade(vec3 albedo, vec3 normal, vec3 to_eye) {
    return shade_lit(albedo, normal, to_eye, 1.0, 1.0);
}

// Colour of a particle's scalar through the colour map, range fixed per clip.
vec3 map_colour(sampler1D colour_map, vec2 range, float value) {
    float t = clamp((value - range.x) / max(range.y - range.x, 1e-30), 0.0, 1.0);
    return texture(colour_map, t).rgb;
}

// The outline of a sphere of radius r centred at `centre` (view space), in a
// plane facing the eye at distance `front` in front of the centre: the plane's
// axes, the direction to the eye, and the outline's half size, so that the
// cone of rays tangent to the sphere meets the plane inside it (at distance
// d - front from the eye, a circle of radius r (d - front) / sqrt(d^2 - r^2)).
// Orthographic views face along z, the outline the sphere's own radius.
struct Outline {
    vec3 axis_x, axis_y, to_eye;
    float half_size;
};
Outline sphere_outline(vec3 centre, float r, float front, bool orthographic) {
    Outline o;
    o.axis_x = vec3(1.0, 0.0, 0.0);
    o.axis_y = vec3(0.0, 1.0, 0.0);
    o.to_eye = vec3(0.0, 0.0, 1.0);
    o.half_size = r;
    if (!orthographic) {
        o.to_eye = normalize(-centre);
        vec3 up = abs(o.to_eye.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        o.axis_x = normalize(cross(up, o.to_eye));
        o.axis_y = cross(o.to_eye, o.axis_x);
        float d = length(centre);
        o.half_size = r * (d - front) / sqrt(max(d * d - r * r, 1e-20));
    }
    return o;
}
