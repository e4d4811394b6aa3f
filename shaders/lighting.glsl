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

// The outline of a sphere of radius r centred at `centre` (view space), in a
// plane facing the eye at distance `front` in front of the centre: the plane's
// axes, the direction to the eye, and the outline's half size, so that the
// cone of rays tangent to the sphere meets the plane inside it (at distance
// d - front from the eye, a circle of radius r (d - front) / sqrt(d^2 - r^2)).
// Orthographic views face along z, the outline the sphere's own radius.
struct Outline {
    vec3 axis_x, axis_y, to_eye;
    float half_size;
};
Outline sphere_outline(vec3 centre, float r, float front, bool orthographic) {
    Outline o;
    o.axis_x = vec3(1.0, 0.0, 0.0);
    o.axis_y = vec3(0.0, 1.0, 0.0);
    o.to_eye = vec3(0.0, 0.0, 1.0);
    o.half_size = r;
    if (!orthographic) {
        o.to_eye = normalize(-centre);
        vec3 up = abs(o.to_eye.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        o.axis_x = normalize(cross(up, o.to_eye));
        o.axis_y = cross(o.to_eye, o.axis_x);
        float d = length(centre);
        o.half_size = r * (d - front) / sqrt(max(d * d - r * r, 1e-20));
    }
    return o;
}
