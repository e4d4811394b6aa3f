in vec3 v_normal;
in vec3 v_position;
flat in vec3 v_albedo;

uniform bool u_orthographic;

out vec4 f_colour;

void main() {
    vec3 to_eye = u_orthographic ? vec3(0.0, 0.0, 1.0) : normalize(-v_position);
    f_colour = vec4(shade(v_albedo, normalize(v_normal), to_eye, v_position, 1.0), 1.0);
}
