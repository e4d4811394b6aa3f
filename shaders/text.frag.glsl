// The glyph's coverage (FreeType's anti-aliasing) as the colour's opacity.
in vec2 v_uv;

uniform vec4 u_colour;
uniform sampler2D u_atlas;

out vec4 f_colour;

void main() {
    f_colour = vec4(u_colour.rgb, u_colour.a * texture(u_atlas, v_uv).r);
}
