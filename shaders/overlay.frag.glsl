in float v_ramp;

uniform vec4 u_colour;
uniform sampler1D u_colour_map;

out vec4 f_colour;

void main() {
    f_colour = v_ramp < 0.0 ? u_colour : vec4(texture(u_colour_map, v_ramp).rgb, 1.0);
}
