// Mesh obstacles (3D): triangles in scene coordinates, one normal per face.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_normal;   // view space
out vec3 v_position; // view space

void main() {
    vec4 position = u_view * vec4(a_position, 1.0);
    v_position = position.xyz;
    v_normal = mat3(u_view) * a_normal;
    gl_Position = u_projection * position;
}
