#include "render/render_settings.hpp"

#include "scene/scene_setup.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace sph {

namespace {

// Whether a block fills the domain across gravity (within half a spacing on
// every axis but gravity's): a pool or a layer, with no room beside it to
// collapse into.
bool fills_floor(const Scene& scene, const FluidBlock& b, const glm::dvec3& g) {
    int down = -1;
    for (int a = 0; a < scene.dimension; ++a)
        if (g[a] != 0 && (down < 0 || std::abs(g[a]) > std::abs(g[down])))
            down = a;
    const double slack = 0.5 * scene.fluid.spacing;
    for (int a = 0; a < scene.dimension; ++a)
        if (a != down &&
            (b.min[a] > scene.domain.min[a] + slack || b.max[a] < scene.domain.max[a] - slack))
            return false;
    return true;
}

// The fastest speed the scene's fluid reaches, m/s, from the height H of a
// source's highest point above the domain's lowest (along gravity) and its
// initial or inlet speed v0. A particle that merely falls keeps v0's energy
// and gains 2 |g| H (Bernoulli, no losses): sqrt(v0^2 + 2 |g| H). With
// `fronts`, a block with room beside it is a dam that breaks: the front of a
// column of depth H running over a dry floor goes at 2 sqrt(|g| H) (Ritter
// 1892; the shallow-water dam break), faster than the fall, as the column's
// pressure pushes its tip; so sqrt(v0^2 + 4 |g| H). H is the block's top
// above the floor: a column standing on the floor is that deep, one held
// above it lands deeper. Emitters' jets and blocks that fill the domain
// across gravity (pools, layers) only fall. 0 when nothing in the scene
// moves or falls.
double fastest_speed(const Scene& scene, bool fronts) {
    glm::dvec3 g(0);
    if (scene.effects.gravity)
        for (int a = 0; a < scene.dimension; ++a)
            g[a] = scene.effects.gravity->acceleration[a];
    const double g_norm = glm::length(g);
    const glm::dvec3 up = g_norm > 0 ? -g / g_norm : glm::dvec3(0);
    // A box's extreme along `up`: its highest corner (or lowest, for low).
    auto height = [&](const Vec3& lo, const Vec3& hi, bool highest) {
        double h = highest ? -1e300 : 1e300;
        for (int corner = 0; corner < 8; ++corner) {
            double d = 0;
            for (int a = 0; a < scene.dimension; ++a)
                d += up[a] * ((corner >> a) & 1 ? hi[a] : lo[a]);
            h = highest ? std::max(h, d) : std::min(h, d);
        }
        return h;
    };
    const double floor = height(scene.domain.min, scene.domain.max, false);
    double fastest = 0;
    auto source = [&](const Vec3& lo, const Vec3& hi, const Vec3& v, bool dam) {
        const double fall = std::max(0.0, height(lo, hi, true) - floor);
        const double v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        fastest = std::max(fastest, std::sqrt(v2 + (dam ? 4 : 2) * g_norm * fall));
    };
    for (const FluidBlock& b : scene.fluid.blocks)
        source(b.min, b.max, b.velocity, fronts && !fills_floor(scene, b, g));
    for (const SceneEmitter& e : scene.effects.emitters)
        source(e.min, e.max, e.velocity, false);
    return fastest;
}

} // namespace

std::array<double, 2> default_colour_range(const Scene& scene, ColourField field) {
    // Nothing in the scene sets a speed (no gravity, fluid at rest, as a
    // drop pulled round by surface tension): a gentle 0.1 m/s.
    auto at_least_gentle = [](double v) {
        return v > 0 ? v : 0.1;
    };
    if (field == ColourField::velocity)
        return {0, at_least_gentle(fastest_speed(scene, true))};
    // Pressure and density follow the fall's speed v = sqrt(v0^2 + 2 |g| H),
    // not a dam's front: the front's tip is the fastest fluid, but thin,
    // and its pressure is low. The pressure that stops a fall: rho0 |g| H
    // under still fluid (the initial speed zero), plus the dynamic pressure
    // rho0 v0^2 / 2 of a source's speed; in zero gravity only the latter.
    const double speed = at_least_gentle(fastest_speed(scene, false));
    const double rho0 = scene.material.rest_density;
    const double pressure = 0.5 * rho0 * speed * speed;
    if (field == ColourField::pressure)
        return {0, pressure};
    // A weakly compressible fluid's density varies with the squared Mach
    // number of its flow, (v / c)^2, c = sqrt(K / rho0) the sound speed
    // (Monaghan 1994, "Simulating free surface flows with SPH", sec. 3).
    // Measured on the 2D dam break (seed solver, v^2 = 2 g H, Ma^2 = 1.1%):
    // 90% of the particles within 1.5%; twice Ma^2 holds 95% or more. At
    // least 1%, so an incompressible solver's fluid, well inside it, shows as
    // the map's grey middle, not as noise. Free-surface particles short of
    // neighbours (spray) fall below it and show as the map's low end.
    const double c2 = scene.material.bulk_modulus / rho0;
    const double compression = std::max(0.01, 2 * speed * speed / std::max(c2, 1e-300));
    return {rho0 * (1 - compression), rho0 * (1 + compression)};
}

namespace {

glm::dvec3 to_dvec3(const Vec3& v) {
    return glm::dvec3(v[0], v[1], v[2]);
}

// The colour field, its map, label and range (an explicit range as given).
void set_colour(const Scene& scene, RenderSettings& r) {
    r.field = scene.render.colour;
    switch (r.field) {
    case ColourField::velocity:
        r.label = "speed (m/s)";
        r.colour_map = ColourMap::viridis;
        break;
    case ColourField::density:
        r.label = "density (kg/m^3)";
        r.colour_map = ColourMap::diverging;
        break;
    case ColourField::pressure:
        r.label = "pressure (Pa)";
        r.colour_map = ColourMap::turbo;
        break;
    }
    if (scene.render.colour_map)
        r.colour_map = *scene.render.colour_map;
    r.range = default_colour_range(scene, r.field);
    if (scene.render.range) {
        r.range = *scene.render.range;
        r.range_key = "render.range";
    }
}

// Where the fluid starts: its blocks, and the emitters' inlets (what
// render.camera.fit = fluid frames at the first frame).
void set_fluid_bounds(const Scene& scene, RenderSettings& r) {
    r.fluid_min = glm::dvec3(1e300);
    r.fluid_max = glm::dvec3(-1e300);
    auto take = [&](const Vec3& lo, const Vec3& hi) {
        for (int a = 0; a < scene.dimension; ++a) {
            r.fluid_min[a] = std::min(r.fluid_min[a], lo[a]);
            r.fluid_max[a] = std::max(r.fluid_max[a], hi[a]);
        }
    };
    for (const FluidBlock& b : scene.fluid.blocks)
        take(b.min, b.max);
    for (const SceneEmitter& e : scene.effects.emitters)
        take(e.min, e.max);
    for (int a = scene.dimension; a < 3; ++a)
        r.fluid_min[a] = r.fluid_max[a] = 0;
}

// render.camera: a fixed camera, a fit, a keyframed path or an orbit.
void set_camera(const Scene& scene, RenderSettings& r) {
    const auto& camera = scene.render.camera;
    r.fov = camera.fov;
    r.camera_fit = camera.fit;
    r.fps = scene.fps;
    r.duration = scene.duration;
    r.frame_to_domain = scene.dimension == 3;
    r.scene_aspect = scene.dimension == 3 ? camera.aspect.value_or(0) : 0;
    r.camera_target = 0.5 * (r.domain_min + r.domain_max);
    if (camera.up)
        r.camera_up = to_dvec3(*camera.up);
    if (camera.target) {
        r.camera_target = to_dvec3(*camera.target);
        r.target_given = true;
    }
    if (camera.centre) {
        r.camera_target = glm::dvec3((*camera.centre)[0], (*camera.centre)[1], 0);
        r.centre_given = true;
    }
    r.view_height = camera.height.value_or(0);
    if (camera.position)
        r.camera_position = to_dvec3(*camera.position);
    r.camera_fixed = camera.position.has_value() || (camera.centre && camera.height);
    for (const auto& k : camera.path) {
        RenderSettings::CameraKeyframe key;
        key.time = k.time;
        if (scene.dimension == 3) {
            key.position = to_dvec3(*k.position);
            key.target = to_dvec3(*k.target);
            if (k.up)
                key.up = to_dvec3(*k.up);
            key.fov = k.fov.value_or(camera.fov);
        } else {
            key.target = glm::dvec3((*k.centre)[0], (*k.centre)[1], 0);
            key.height = *k.height;
        }
        r.camera_path.push_back(key);
    }
    if (!r.camera_path.empty())
        r.camera_fixed = false;
    if (camera.orbit) {
        r.orbit =
            RenderSettings::Orbit{camera.orbit->turns, camera.orbit->elevation_deg,
                                  camera.orbit->start_deg, camera.orbit->distance.value_or(0)};
        r.camera_fixed = false;
    }
}

// Light and depth, and which way is up for the floor.
void set_light(const Scene& scene, RenderSettings& r) {
    r.cull_buried = scene.dimension == 3 && scene.render.cull_buried;
    r.shadows = scene.render.shadows;
    r.ambient_occlusion = scene.render.ambient_occlusion;
    r.floor = scene.render.floor;
    r.tank = scene.render.tank;
    r.background = scene.render.background;
    // The floor lies across gravity's largest component, on the side it
    // pulls to; without gravity, under y.
    if (scene.effects.gravity) {
        const auto& g = scene.effects.gravity->acceleration;
        int axis = -1;
        for (int a = 0; a < scene.dimension; ++a)
            if (g[a] != 0 && (axis < 0 || std::abs(g[a]) > std::abs(g[axis])))
                axis = a;
        if (axis >= 0) {
            r.up = glm::dvec3(0);
            r.up[axis] = g[axis] < 0 ? 1 : -1;
        }
    }
}

} // namespace

RenderSettings make_render_settings(const Scene& scene) {
    RenderSettings r;
    r.width = scene.render.size[0];
    r.height = scene.render.size[1];
    r.dimension = scene.dimension;
    r.title = scene.render.title.value_or("");
    r.caption = scene.render.caption.value_or(r.caption);
    r.font = scene.render.font.value_or("");
    r.spheres = scene.render.spheres;
    r.radius = 0.5 * scene.fluid.spacing;
    r.style = scene.render.style;
    r.spacing = scene.fluid.spacing;
    r.surface = {.voxel = scene.render.surface.voxel,
                 .radius = scene.render.surface.radius,
                 .smoothing = scene.render.surface.smoothing};
    for (int a = 0; a < scene.dimension; ++a) {
        r.domain_min[a] = scene.domain.min[a];
        r.domain_max[a] = scene.domain.max[a];
    }
    r.obstacles = scene.effects.obstacles;
    r.paddles = make_paddles<3>(scene);
    set_colour(scene, r);
    set_camera(scene, r);
    set_fluid_bounds(scene, r);
    set_light(scene, r);
    return r;
}

} // namespace sph
