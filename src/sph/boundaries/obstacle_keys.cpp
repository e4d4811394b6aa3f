#include "sph/boundaries/obstacle_keys.hpp"

namespace sph {

const KeyList<SceneObstacle>& obstacle_keys() {
    using S = SceneObstacle;
    // (Tables of their own: GCC 12 fails on them nested in the list's aggregate.)
    static const KeyTable<S> box_keys{{.path = "min",
                                       .field = &S::min,
                                       .unit = "m",
                                       .doc = "Lower corner of a box obstacle.",
                                       .absent = "required",
                                       .required = true},
                                      {.path = "max",
                                       .field = &S::max,
                                       .unit = "m",
                                       .doc = "Upper corner of a box obstacle.",
                                       .absent = "required",
                                       .required = true}};
    static const KeyTable<S> sphere_keys{{.path = "centre",
                                          .field = &S::centre,
                                          .unit = "m",
                                          .doc = "Centre of a sphere obstacle (a circle in 2D).",
                                          .absent = "required",
                                          .required = true},
                                         {.path = "radius",
                                          .field = &S::radius,
                                          .unit = "m",
                                          .doc = "Radius of a sphere obstacle.",
                                          .bound = Bound::positive,
                                          .absent = "required",
                                          .required = true}};
    static const KeyTable<S> mesh_keys{
        {.path = "file",
         .field = &S::mesh_file,
         .doc = "Wavefront OBJ file of a closed triangle mesh obstacle (3D only), "
                "relative to the scene file's folder (not absolute, no \"..\").",
         .absent = "required",
         .required = true},
        {.path = "scale",
         .field = &S::mesh_scale,
         .unit = "m per file unit",
         .doc = "Scale of a mesh obstacle: a vertex v of the file is at scale v + "
                "offset.",
         .bound = Bound::positive},
        // Always 3 numbers: a mesh is 3D (a 2D scene is refused).
        {.path = "offset",
         .field = &S::mesh_offset,
         .unit = "m",
         .doc = "Offset of a mesh obstacle, added after scaling.",
         .size = VectorSize::three}};
    static const KeyList<S> keys{
        .path = "effects.obstacles",
        .doc = "Static obstacles the fluid flows around (wcsph, dfsph): each {\"box\": {...}}, "
               "{\"sphere\": {...}} or (3D) {\"mesh\": {...}}, made of boundary particles.",
        .alternatives = {{.key = "box",
                          .value = static_cast<int>(ObstacleShape::box),
                          .keys = box_keys,
                          .missing = "a box obstacle needs min and max"},
                         {.key = "sphere",
                          .value = static_cast<int>(ObstacleShape::sphere),
                          .keys = sphere_keys,
                          .missing = "a sphere obstacle needs centre and radius"},
                         {.key = "mesh",
                          .value = static_cast<int>(ObstacleShape::mesh),
                          .keys = mesh_keys,
                          .missing = "a mesh obstacle needs the OBJ file's name",
                          .min_dimension = 3,
                          .too_few =
                              "a mesh obstacle is a 3D solid; a 2D scene has boxes and spheres "
                              "(circles) only"}},
        .which = enum_field<&S::shape>(),
        .several = "an obstacle is one of box, sphere or mesh, not several",
        .none = "expected {\"box\": {\"min\": [...], \"max\": [...]}}, {\"sphere\": {\"centre\": "
                "[...], \"radius\": r}} or (3D) {\"mesh\": {\"file\": \"name.obj\"}}",
    };
    return keys;
}

} // namespace sph
