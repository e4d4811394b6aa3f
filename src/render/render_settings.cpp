#include "render/render_settings.hpp"

#include "io/scene_setup.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

RenderSettings make_render_settings(const Scene& scene) {
    RenderSettings r;
    r.width = scene.render.size[0];
    r.height = scene.render.size[1];
    r.dimension = scene.dimension;
    r.field = scene.render.colour;
    r.spheres = scene.render.spheres;
    r.radius = 0.5 * scene.fluid.spacing;
    for (int a = 0; a < scene.dimension; ++a) {
        r.domain_min[a] = scene.domain.min[a];
        r.domain_max[a] = scene.domain.max[a];
    }
    r.obstacles = scene.effects.obstacles;
    r.paddles = make_paddles<3>(scene);
    // Physical scales of the scene for ranges it does not fix.
    const double height = r.domain_max.y - r.domain_min.y;
    double g = 0;
    if (scene.effects.gravity)
        for (int a = 0; a < scene.dimension; ++a)
            g += scene.effects.gravity->acceleration[a] * scene.effects.gravity->acceleration[a];
    g = std::sqrt(g);
    double block_speed = 0;
    for (const auto& b : scene.fluid.blocks)
        block_speed =
            std::max(block_speed, std::hypot(b.velocity[0], b.velocity[1], b.velocity[2]));
    const double rho0 = scene.material.rest_density;
    if (r.field == "velocity") {
        r.label = "speed (m/s)";
        r.colour_map = "viridis";
        // Nothing in the scene sets a speed (no gravity, a block at rest, as
        // a drop pulled round by surface tension): a gentle 0.1 m/s.
        const double top = std::sqrt(2 * g * height) + block_speed;
        r.range = {0, top > 0 ? top : 0.1};
    } else if (r.field == "density") {
        r.label = "density (kg/m^3)";
        r.colour_map = "diverging";
        r.range = {0.97 * rho0, 1.03 * rho0};
    } else {
        r.label = "pressure (Pa)";
        r.colour_map = "turbo";
        const double top = rho0 * g * height;
        r.range = {0, top > 0 ? top : 0.5 * rho0 * 0.1 * 0.1}; // as for speed
    }
    if (scene.render.colour_map != "auto")
        r.colour_map = scene.render.colour_map;
    if (scene.render.range)
        r.range = *scene.render.range;

    r.fov = scene.render.camera.fov;
    const glm::dvec3 centre = 0.5 * (r.domain_min + r.domain_max);
    r.camera_target = centre;
    if (scene.render.camera.target)
        r.camera_target = {(*scene.render.camera.target)[0], (*scene.render.camera.target)[1],
                           (*scene.render.camera.target)[2]};
    if (scene.render.camera.position) {
        r.camera_position = {(*scene.render.camera.position)[0], (*scene.render.camera.position)[1],
                             (*scene.render.camera.position)[2]};
    } else {
        // From the front, right and above, at the distance where the domain's
        // bounding sphere would just fit the vertical field of view; a box
        // fills less than its sphere, so come a little closer.
        const double radius = 0.5 * glm::length(r.domain_max - r.domain_min);
        const double distance = 0.85 * radius / std::sin(glm::radians(0.5 * r.fov));
        r.camera_position = r.camera_target + distance * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
    }
    r.cull_buried = scene.dimension == 3 && scene.render.cull_buried;
    return r;
}

} // namespace sph
