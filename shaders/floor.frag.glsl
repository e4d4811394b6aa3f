// The floor as a shadow catcher: where the key light reaches it, it is the
// backdrop itself (so it meets the overlay's bands and the horizon without a
// seam); where the light is blocked it darkens as a matte floor would, by
// the share of its light the shadow takes (ambient against ambient plus
// key, in linear light). It fades out with the distance from the domain's
// centre, where the shadow map ends.
in vec3 v_position;
in vec3 v_scene;

uniform vec3 u_top, u_bottom; // sRGB, the backdrop's gradient
uniform float u_image_height; // px
uniform vec2 u_fade;          // m: fully there inside .x, gone beyond .y
uniform vec3 u_floor_up;      // scene coordinates

out vec4 f_colour;

void main() {
    vec3 backdrop = srgb_to_linear(mix(u_bottom, u_top, gl_FragCoord.y / u_image_height));
    float facing = max(dot(u_up, u_light), 0.0);
    float visible = facing > 0.0 ? key_visibility(v_position, u_up) : 1.0;
    // A floor's ambient, brighter than a sphere's: the shadow reads, but
    // stays a shadow, not a hole.
    const float ambient = 0.5;
    float light = (ambient + 0.85 * facing * visible) / (ambient + 0.85 * facing);
    vec3 along = v_scene - dot(v_scene, u_floor_up) * u_floor_up;
    float fade = 1.0 - smoothstep(u_fade.x, u_fade.y, length(along));
    f_colour = vec4(linear_to_srgb(backdrop * light), fade);
}
