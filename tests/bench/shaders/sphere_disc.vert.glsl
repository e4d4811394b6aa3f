// A sphere only a few pixels across (DrawVariant::flat_below_px) as a flat
// disc facing the eye at the sphere's front, lit as a sphere seen from afar:
// no ray cast and no depth written, so the rasteriser may test depth before
// shading. POINTS: one point sprite per sphere; otherwise the impostor's
// instanced outline.
#ifndef POINTS
layout(location = 0) in vec2 a_corner; // outline corner, around the unit circle
#endif
layout(location = 1) in vec3 a_centre;  // world space
layout(location = 2) in float a_scalar; // the coloured field

uniform mat4 u_view;
uniform mat4 u_projection;
uniform float u_radius;
uniform bool u_orthographic;
uniform sampler1D u_colour_map;
uniform vec2 u_range;
uniform float u_viewport_height; // px

#ifdef POINTS
flat out float v_scale; // disc radii per half point size
#else
out vec2 v_disc; // the point in the disc, 1 on the silhouette
#endif
flat out vec3 v_albedo; // linear

void main() {
    vec3 centre = (u_view * vec4(a_centre, 1.0)).xyz;
    // As the impostor's outline, in the plane touching the sphere's front.
    Outline o = sphere_outline(centre, u_radius, u_radius, u_orthographic);
    vec3 front = centre + u_radius * o.to_eye;
    v_albedo = srgb_to_linear(map_colour(u_colour_map, u_range, a_scalar));
#ifdef POINTS
    gl_Position = u_projection * vec4(front, 1.0);
    // The disc's radius in pixels: projection[1][1] takes view-space y to
    // clip space, and one unit of clip y / w is half the viewport's height.
    float radius_px = o.half_size * u_projection[1][1] * 0.5 * u_viewport_height / gl_Position.w;
    gl_PointSize = 2.0 * radius_px + 1.0; // a pixel of room for the disc's off-centre image
    v_scale = gl_PointSize / (2.0 * radius_px);
#else
    v_disc = a_corner;
    gl_Position = u_projection *
                  vec4(front + o.half_size * (a_corner.x * o.axis_x + a_corner.y * o.axis_y), 1.0);
#endif
}
