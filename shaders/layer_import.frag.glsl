// One rank's layer written into the frame, sample by sample (reading
// gl_SampleID runs this once per sample): its colour, and as depth the very
// float its fragment wrote, so the depth test keeps the nearest as it would
// had the frame drawn the rank's spheres itself (render/depth_composite.hpp).
uniform sampler2D u_colour;
uniform usampler2D u_depth_bits;
uniform int u_samples;
uniform uint u_group_bit;

out vec4 f_colour;

void main() {
    ivec2 flat_xy = ivec2(int(gl_FragCoord.x) * u_samples + gl_SampleID, int(gl_FragCoord.y));
    uint bits = texelFetch(u_depth_bits, flat_xy, 0).r;
    // No sphere of this rank at this sample, or one of the other group.
    if (bits == 0xffffffffu || (bits & 0x40000000u) != u_group_bit)
        discard;
    gl_FragDepth = uintBitsToFloat(bits & 0x3fffffffu);
    f_colour = texelFetch(u_colour, flat_xy, 0);
}
