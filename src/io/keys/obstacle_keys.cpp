// The effects.obstacles family's keys, read, checked and written by hand: a list of one-of shapes.
// (Their declarations move next to the family once it has its own folder.)
#include "io/keys/scene_keys.hpp"
#include "io/obj_mesh.hpp"
#include "io/scene_paths.hpp"

namespace sph {

void read_obstacles(FieldReader& r, int dim, const std::string& file,
                    std::vector<SceneObstacle>& obstacles) {
    const std::size_t count =
        r.list("effects.obstacles", "none",
               "Static obstacles the fluid flows around (wcsph, dfsph): each {\"box\": {...}}, "
               "{\"sphere\": {...}} or (3D) {\"mesh\": {...}}, made of boundary particles.");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.obstacles[{}]", i);
        const auto min = r.optional_vector(p + ".box.min", dim, "m", "required",
                                           "Lower corner of a box obstacle.");
        const auto max = r.optional_vector(p + ".box.max", dim, "m", "required",
                                           "Upper corner of a box obstacle.");
        const auto centre = r.optional_vector(p + ".sphere.centre", dim, "m", "required",
                                              "Centre of a sphere obstacle (a circle in 2D).");
        const auto radius = r.optional_number(p + ".sphere.radius", "m", "required",
                                              "Radius of a sphere obstacle.", Bound::positive);
        const json* box = r.find(p + ".box");
        const json* sphere = r.find(p + ".sphere");
        const json* mesh = r.find(p + ".mesh");
        if (i < count && mesh && dim == 2)
            r.fail(p + ".mesh", "a mesh obstacle is a 3D solid; a 2D scene has boxes and spheres "
                                "(circles) only");
        const auto mesh_file = r.optional_text(
            p + ".mesh.file", "required",
            "Wavefront OBJ file of a closed triangle mesh obstacle (3D only), relative to the "
            "scene file's folder (not absolute, no \"..\").");
        const double mesh_scale =
            r.number(p + ".mesh.scale", 1, "m per file unit",
                     "Scale of a mesh obstacle: a vertex v of the file is at scale v + offset.",
                     Bound::positive);
        // Always 3 numbers: a mesh is 3D (a 2D scene was refused above).
        const Vec3 mesh_offset = r.vector(p + ".mesh.offset", {0, 0, 0}, 3, "m",
                                          "Offset of a mesh obstacle, added after scaling.");
        if (i >= count)
            break;
        SceneObstacle o;
        const int shapes = (box != nullptr) + (sphere != nullptr) + (mesh != nullptr);
        if (shapes != 1)
            r.fail(p, shapes > 1 ? "an obstacle is one of box, sphere or mesh, not several"
                                 : "expected {\"box\": {\"min\": [...], \"max\": [...]}}, "
                                   "{\"sphere\": {\"centre\": [...], \"radius\": r}} or (3D) "
                                   "{\"mesh\": {\"file\": \"name.obj\"}}");
        const json* given = box ? box : sphere ? sphere : mesh;
        const std::string shape = p + (box ? ".box" : sphere ? ".sphere" : ".mesh");
        if (!given->is_object())
            r.fail(shape, "expected an object, got " + describe(*given));
        if (box) {
            if (!min || !max)
                r.fail(shape + (min ? ".max" : ".min"), "a box obstacle needs min and max");
            o.shape = ObstacleShape::box;
            o.min = *min;
            o.max = *max;
        } else if (sphere) {
            if (!centre || !radius)
                r.fail(shape + (centre ? ".radius" : ".centre"),
                       "a sphere obstacle needs centre and radius");
            o.shape = ObstacleShape::sphere;
            o.centre = *centre;
            o.radius = *radius;
        } else {
            if (!mesh_file)
                r.fail(shape + ".file", "a mesh obstacle needs the OBJ file's name");
            o.shape = ObstacleShape::mesh;
            o.mesh_file = *mesh_file;
            o.mesh_scale = mesh_scale;
            o.mesh_offset = mesh_offset;
            // Relative to the scene's own folder, and inside it, as a scene
            // from elsewhere must not read files outside it.
            const std::filesystem::path folder = std::filesystem::path(file).parent_path();
            try {
                const std::filesystem::path path = resolve_inside(
                    folder.empty() ? "." : folder, *mesh_file, file, shape + ".file");
                o.mesh = read_obj_mesh(path, mesh_scale,
                                       {mesh_offset[0], mesh_offset[1], mesh_offset[2]}, file,
                                       shape + ".file");
            } catch (const InputError& e) {
                r.fail(e.field, e.problem);
            }
        }
        obstacles.push_back(o);
    }
}

json write_obstacles(const std::vector<SceneObstacle>& obstacles, int dim) {
    auto vec = [dim](const Vec3& v) {
        return std::vector<double>(v.begin(), v.begin() + dim);
    };
    json out = json::array();
    for (const auto& o : obstacles)
        out.push_back(o.shape == ObstacleShape::box
                          ? json{{"box", {{"min", vec(o.min)}, {"max", vec(o.max)}}}}
                      : o.shape == ObstacleShape::sphere
                          ? json{{"sphere", {{"centre", vec(o.centre)}, {"radius", o.radius}}}}
                          // The file as the scene names it, relative to the scene's folder.
                          : json{{"mesh",
                                  {{"file", o.mesh_file},
                                   {"scale", o.mesh_scale},
                                   {"offset", vec(o.mesh_offset)}}}});
    return out;
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
