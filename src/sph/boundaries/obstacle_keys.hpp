#pragma once
// The scene's `effects.obstacles`: static solids the fluid flows around
// (obstacles.hpp builds them), each a box, a sphere (a circle in 2D) or, in
// 3D, a closed triangle mesh from an OBJ file, and their keys.

#include "sph/boundaries/obstacles.hpp"
#include "sph/scene_key.hpp"

#include <memory>
#include <optional>
#include <string>

namespace sph {

struct SceneObstacle {
    ObstacleShape shape = ObstacleShape::box;
    Vec3 min{0, 0, 0}, max{0, 0, 0};      // m, the box's corners
    Vec3 centre{0, 0, 0};                 // m, the sphere's centre
    double radius = 0;                    // m, the sphere's radius
    std::optional<std::string> mesh_file; // the mesh's OBJ file as the scene names it
    double mesh_scale = 1;                // file units to m
    Vec3 mesh_offset{0, 0, 0};            // m, added after scaling
    // Read when the scene loads (scene/), in scene coordinates: the file is read
    // once and the simulation and the renderer share it.
    std::shared_ptr<const TriangleMesh> mesh;
};

// effects.obstacles: a list of {"box": ...}, {"sphere": ...} or {"mesh": ...}.
const KeyList<SceneObstacle>& obstacle_keys();

} // namespace sph
