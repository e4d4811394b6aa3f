// Sphere impostor: one camera-facing outline per particle (instanced), a
// triangle or a square around the sphere's exact silhouette (the unit circle
// in corner coordinates); the fragment shader ray-casts the sphere.
layout(location = 0) in vec2 a_corner;  // outline corner, around the unit circle
layout(location = 1) in vec3 a_centre;  // per instance, world space
layout(location = 2) in float a_scalar; // per instance, the coloured field

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;
uniform bool u_orthographic;
uniform sampler1D u_colour_map;
uniform vec2 u_range;

out vec3 v_point;        // view-space point on the quad
flat out vec3 v_centre;  // view-space sphere centre
flat out vec3 v_colour;

void main() {
    vec3 centre = (u_view * vec4(a_centre, 1.0)).xyz;
    vec3 axis_x = vec3(1.0, 0.0, 0.0);
    vec3 axis_y = vec3(0.0, 1.0, 0.0);
    vec3 to_eye = vec3(0.0, 0.0, 1.0);
    float half_size = u_radius;
    // How far in front of the centre the quad lies: at the front, every
    // ray-cast depth lies behind the quad's (conservative depth).
#ifdef CONSERVATIVE_DEPTH
    float front = u_radius;
#else
    float front = 0.0;
#endif
    if (!u_orthographic) {
        // Face the eye; the cone of rays tangent to the sphere meets the plane
        // at distance d - front from the eye in a circle of radius
        // r (d - front) / sqrt(d^2 - r^2).
        to_eye = normalize(-centre);
        vec3 up = abs(to_eye.y) < 0.99 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
        axis_x = normalize(cross(up, to_eye));
        axis_y = cross(to_eye, axis_x);
        float d = length(centre);
        half_size = u_radius * (d - front) / sqrt(max(d * d - u_radius * u_radius, 1e-20));
    }
    v_point = centre + front * to_eye + half_size * (a_corner.x * axis_x + a_corner.y * axis_y);
    v_centre = centre;
    v_colour = map_colour(u_colour_map, u_range, a_scalar);
    gl_Position = u_projection * vec4(v_point, 1.0);
}
