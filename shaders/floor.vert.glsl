// The floor (3D): a square in scene coordinates under the domain.
layout(location = 0) in vec3 a_position;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_position; // view space
out vec3 v_scene;    // scene coordinates, relative to the domain's centre

void main() {
    vec4 position = u_view * vec4(a_position, 1.0);
    v_position = position.xyz;
    v_scene = a_position;
    gl_Position = u_projection * position;
}
