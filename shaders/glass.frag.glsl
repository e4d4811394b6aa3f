// The tank's walls as faint glass (3D): a clear pane that reflects more of
// the sky at grazing angles (Schlick's Fresnel term, glass F0 = 0.04), so
// its faces read without hiding the fluid behind them.
in vec3 v_normal;
in vec3 v_position;

uniform vec3 u_colour; // sRGB, the tint

out vec4 f_colour;

void main() {
    vec3 to_eye = normalize(-v_position);
    // Only the walls behind the fluid: a wall whose outside faces the eye
    // stands between the camera and the tank's inside, and from close by
    // (render.camera.fit = fluid) it covered the whole view as a pale pane.
    if (dot(v_normal, to_eye) > 0.0)
        discard;
    float facing = min(abs(dot(normalize(v_normal), to_eye)), 1.0);
    float fresnel = 0.04 + 0.96 * pow(1.0 - facing, 5.0);
    f_colour = vec4(u_colour, clamp(0.05 + 0.5 * fresnel, 0.0, 0.35));
}
