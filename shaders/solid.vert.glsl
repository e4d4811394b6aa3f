// Lit meshes in scene coordinates: the mesh obstacles (3D, one normal per
// face), and the fluid's surface (render.style = surface; vertices relative
// to the camera's origin, normals out of the fluid), which with VERTEX_SCALAR
// defined also carries the colour field per vertex.
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
#ifdef VERTEX_SCALAR
layout(location = 2) in float a_scalar;
out float v_scalar;
#endif

uniform mat4 u_view;
uniform mat4 u_projection;

out vec3 v_normal;   // view space
out vec3 v_position; // view space

void main() {
    vec4 position = u_view * vec4(a_position, 1.0);
    v_position = position.xyz;
    v_normal = mat3(u_view) * a_normal;
#ifdef VERTEX_SCALAR
    v_scalar = a_scalar;
#endif
    gl_Position = u_projection * position;
}
