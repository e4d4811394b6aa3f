in vec3 v_normal;
in vec3 v_position;

uniform vec3 u_colour;

out vec4 f_colour;

void main() {
    // Lit as the particles are; a face seen from behind (inside the solid,
    // through the near plane) is lit from its other side.
    vec3 normal = normalize(gl_FrontFacing ? v_normal : -v_normal);
    f_colour = vec4(shade(srgb_to_linear(u_colour), normal, normalize(-v_position), v_position, 0.3), 1.0);
}
