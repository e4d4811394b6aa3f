// The backdrop: a vertical gradient over the whole image (sRGB values),
// lighter at the top, as a studio's sweep behind the scene.
in vec2 v_uv;

uniform vec3 u_top, u_bottom;
uniform float u_image_height; // px

out vec4 f_colour;

void main() {
    // gl_FragCoord, not v_uv: a band drawn under a scissor continues the
    // gradient the scene's rectangle shows.
    float t = gl_FragCoord.y / u_image_height;
    f_colour = vec4(mix(u_bottom, u_top, t), 1.0);
}
