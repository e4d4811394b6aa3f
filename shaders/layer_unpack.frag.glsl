// A rank's multisampled layer laid out flat for reading back: pixel (x, y)
// of the layer's sample s goes to (x * samples + s, y)
// (render/depth_composite.hpp).
uniform sampler2DMS u_colour;
uniform usampler2DMS u_depth_bits;
uniform int u_samples;

layout(location = 0) out vec4 f_colour;
layout(location = 1) out uint f_depth_bits;

void main() {
    ivec2 flat_xy = ivec2(gl_FragCoord.xy);
    ivec2 pixel = ivec2(flat_xy.x / u_samples, flat_xy.y);
    int s = flat_xy.x - pixel.x * u_samples;
    f_colour = texelFetch(u_colour, pixel, s);
    f_depth_bits = texelFetch(u_depth_bits, pixel, s).r;
}
