// Multiplies the frame by its occlusion (blending: destination times
// source), averaged over the 4x4 cell of the occlusion pass's pattern.
in vec2 v_uv;

uniform sampler2D u_occlusion;

out vec4 f_colour;

void main() {
    ivec2 size = textureSize(u_occlusion, 0);
    ivec2 p = ivec2(gl_FragCoord.xy);
    float sum = 0.0;
    for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x)
            sum += texelFetch(u_occlusion, clamp(p + ivec2(x, y), ivec2(0), size - 1), 0).r;
    f_colour = vec4(vec3(sum / 16.0), 1.0);
}
