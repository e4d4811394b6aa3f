// Lines, the colour bar and text: positions through one transform (the
// camera for the domain box, a pixel grid for the rest).
layout(location = 0) in vec3 a_position;
layout(location = 1) in float a_ramp; // colour-map coordinate, < 0 for the flat colour

uniform mat4 u_transform;

out float v_ramp;

void main() {
    v_ramp = a_ramp;
    gl_Position = u_transform * vec4(a_position, 1.0);
}
