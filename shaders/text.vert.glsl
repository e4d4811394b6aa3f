// Glyph quads in pixels, with their place in the glyph atlas.
layout(location = 0) in vec2 a_position;
layout(location = 1) in vec2 a_uv;

uniform mat4 u_transform;

out vec2 v_uv;

void main() {
    v_uv = a_uv;
    gl_Position = u_transform * vec4(a_position, 0.0, 1.0);
}
