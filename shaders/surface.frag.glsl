// Water-like shading of the surface: the colour field as the body colour,
// lit by the spheres' light (fixed to the camera), a sharp highlight, and a
// sky reflected by Schlick's Fresnel term (Schlick 1994, "An inexpensive
// BRDF model for physically-based rendering", eq. 15) with water's normal
// reflectance F0 = ((1.33 - 1) / (1.33 + 1))^2 = 0.02: the surface mirrors
// the sky at grazing angles and shows its body face on. 2D (u_flat): the
// region filled flat, the outline lightened.
in vec3 v_position;
in vec3 v_normal;
in float v_scalar;

uniform mat4 u_view;
uniform bool u_orthographic;
uniform bool u_flat;
uniform float u_lighten; // 0 the fill, > 0 the outline (2D)
uniform sampler1D u_colour_map;
uniform vec2 u_range;

out vec4 f_colour;

void main() {
    vec3 base = map_colour(u_colour_map, u_range, v_scalar);
    if (u_flat) {
        f_colour = vec4(mix(base, vec3(1.0), u_lighten), 1.0);
        return;
    }
    vec3 to_eye = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position);
    vec3 n = normalize(v_normal);
    // A face seen from behind (cut open by the near plane) is lit as its front.
    if (dot(n, to_eye) < 0.0)
        n = -n;
    const vec3 light = normalize(vec3(0.35, 0.6, 0.7));
    float diffuse = max(dot(n, light), 0.0);
    // The powers as products (120 = 64 + 32 + 16 + 8; 5 = 4 + 1): llvmpipe's
    // pow() is an exp2 of a log2, dearer and no more exact.
    float h = max(dot(n, normalize(light + to_eye)), 0.0);
    float h2 = h * h, h4 = h2 * h2, h8 = h4 * h4, h16 = h8 * h8, h32 = h16 * h16;
    float specular = (h32 * h32) * h32 * h16 * h8;
    float grazing = 1.0 - clamp(dot(n, to_eye), 0.0, 1.0);
    float grazing2 = grazing * grazing;
    float fresnel = 0.02 + 0.98 * grazing2 * grazing2 * grazing;
    // The reflected ray in world space (y up): a dark floor colour below the
    // horizon, a pale sky above.
    vec3 reflected = transpose(mat3(u_view)) * reflect(-to_eye, n);
    vec3 sky = mix(vec3(0.20, 0.22, 0.26), vec3(0.62, 0.70, 0.80),
                   smoothstep(-0.2, 0.6, reflected.y));
    vec3 body = base * (0.35 + 0.65 * diffuse);
    f_colour = vec4(mix(body, sky, fresnel) + vec3(0.45) * specular, 1.0);
}
