// Shared by every sphere technique, so impostors and meshes are lit the same:
// one directional light fixed to the camera, Lambert diffuse, ambient, and a
// small Blinn-Phong highlight that shows the spheres' roundness.
vec3 shade(vec3 base, vec3 normal, vec3 to_eye) {
    const vec3 light = normalize(vec3(0.35, 0.6, 0.7));
    float diffuse = max(dot(normal, light), 0.0);
    float specular = pow(max(dot(normal, normalize(light + to_eye)), 0.0), 40.0);
    return base * (0.3 + 0.7 * diffuse) + vec3(0.22) * specular;
}

// Colour of a particle's scalar through the colour map, range fixed per clip.
vec3 map_colour(sampler1D colour_map, vec2 range, float value) {
    float t = clamp((value - range.x) / max(range.y - range.x, 1e-30), 0.0, 1.0);
    return texture(colour_map, t).rgb;
}
