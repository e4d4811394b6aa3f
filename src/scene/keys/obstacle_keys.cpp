// effects.obstacles: the keys are declared in sph/boundaries/obstacle_keys.cpp;
// here a mesh's file is read, and each obstacle is checked against the scene.
#include "scene/key_walk.hpp"
#include "scene/keys/scene_keys.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene_paths.hpp"

namespace sph {

std::vector<SceneObstacle> read_obstacles(FieldReader& r, int dim, const std::string& file) {
    return read_list(r, obstacle_keys(), dim, [&](SceneObstacle& o, const std::string& shape) {
        if (o.shape != ObstacleShape::mesh)
            return;
        // Relative to the scene's own folder, and inside it, as a scene from
        // elsewhere must not read files outside it.
        const std::filesystem::path folder = std::filesystem::path(file).parent_path();
        try {
            const std::filesystem::path path =
                resolve_inside(folder.empty() ? "." : folder, *o.mesh_file, file, shape + ".file");
            o.mesh = read_obj_mesh(path, o.mesh_scale,
                                   {o.mesh_offset[0], o.mesh_offset[1], o.mesh_offset[2]}, file,
                                   shape + ".file");
        } catch (const InputError& e) {
            r.fail(e.field, e.problem);
        }
    });
}

double check_obstacle(const FieldReader& r, const Scene& s, std::size_t i, double layers) {
    const SceneObstacle& o = s.effects.obstacles[i];
    const int dim = s.dimension;
    const double spacing = s.fluid.spacing;
    const std::string p = fmt::format("effects.obstacles[{}]", i);
    auto outside = [&](double lo, double hi, int a) {
        const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
        return lo < s.domain.min[a] - tolerance || hi > s.domain.max[a] + tolerance;
    };
    if (o.shape == ObstacleShape::box) {
        double sites = 1, interior = 1;
        for (int a = 0; a < dim; ++a) {
            if (!(o.min[a] < o.max[a]))
                r.fail(p + ".box",
                       fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                   "xyz"[a], o.min[a], o.max[a]));
            if (outside(o.min[a], o.max[a], a))
                r.fail(p + ".box",
                       fmt::format("the box [{}, {}] on axis {} is outside the domain [{}, {}]",
                                   o.min[a], o.max[a], "xyz"[a], s.domain.min[a], s.domain.max[a]));
            const double along = (o.max[a] - o.min[a]) / spacing;
            if (!(along >= 1 - 1e-9))
                r.fail(p + ".box",
                       fmt::format("the box is thinner than one spacing ({} m) on axis {}: too "
                                   "thin a solid for the fluid to see",
                                   spacing, "xyz"[a]));
            sites *= std::max(1.0, std::round(along));
            interior *= std::max(0.0, std::round(along) - 2 * layers);
        }
        return sites - interior;
    }
    if (o.shape == ObstacleShape::mesh) {
        // The mesh's bounding box, as a box obstacle's own.
        const Box<3>& bounds = o.mesh->bounds();
        double sites = 1;
        for (int a = 0; a < dim; ++a) {
            if (outside(bounds.min[a], bounds.max[a], a))
                r.fail(p + ".mesh",
                       fmt::format("the mesh (scaled and moved) spans [{}, {}] on axis {}, outside "
                                   "the domain [{}, {}]",
                                   bounds.min[a], bounds.max[a], "xyz"[a], s.domain.min[a],
                                   s.domain.max[a]));
            const double along = (bounds.max[a] - bounds.min[a]) / spacing;
            if (!(along >= 1 - 1e-9))
                r.fail(p + ".mesh",
                       fmt::format("the mesh (scaled) is thinner than one spacing ({} m) on axis "
                                   "{}: too thin a solid for the fluid to see",
                                   spacing, "xyz"[a]));
            sites *= std::max(1.0, std::round(along));
        }
        // The shell is about its area times its depth; twice that allows for
        // curvature and the lattice, and no more than its bounding box holds.
        return std::min(sites, 2 * o.mesh->area() / (spacing * spacing) * layers + 1);
    }
    for (int a = 0; a < dim; ++a)
        if (outside(o.centre[a], o.centre[a], a))
            r.fail(p + ".sphere.centre",
                   fmt::format("{} on axis {} is outside the domain [{}, {}]", o.centre[a],
                               "xyz"[a], s.domain.min[a], s.domain.max[a]));
    if (!(2 * o.radius >= spacing * (1 - 1e-9)))
        r.fail(p + ".sphere.radius",
               fmt::format("{} m is less than half a spacing ({} m): too small a solid for the "
                           "fluid to see",
                           o.radius, spacing));
    for (int a = 0; a < dim; ++a)
        if (outside(o.centre[a] - o.radius, o.centre[a] + o.radius, a))
            r.fail(p + ".sphere.radius",
                   fmt::format("the sphere reaches outside the domain on axis {} ([{}, {}] against "
                               "[{}, {}])",
                               "xyz"[a], o.centre[a] - o.radius, o.centre[a] + o.radius,
                               s.domain.min[a], s.domain.max[a]));
    const double around = dim == 2 ? 2 * M_PI * o.radius / spacing
                                   : 4 * M_PI * o.radius * o.radius / (spacing * spacing);
    return layers * (around + 1);
}

} // namespace sph
