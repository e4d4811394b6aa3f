#pragma once
// The key tables of the scene's own objects (the solver's, the effects', the
// boundaries' and the sources' are in their files under sph/), and the checks
// of obstacles and paddles against the rest of the scene. The scene reads and
// writes itself from these (scene/scene.cpp).

#include "scene/field_reader.hpp"
#include "scene/scene.hpp"

namespace sph {

// dimension, duration, fps.
const KeyTable<Scene>& top_level_keys();
const KeyTable<Scene::Domain>& domain_keys();
// The fluid's scalars; its blocks are a list of block_keys().
const KeyTable<Scene::Fluid>& fluid_keys();
const KeyTable<FluidBlock>& block_keys();
const KeyTable<Scene::Material>& material_keys();
const KeyTable<Scene::Watchdog>& watchdog_keys();
// render_keys.cpp
const KeyTable<Scene::Render>& render_keys();
const KeyTable<Scene::Render::Camera>& camera_keys();
const KeyList<Scene::Render::Camera::Keyframe>& camera_path_keys();
const KeyTable<Scene::Render::Camera::Orbit>& orbit_keys();
// Reads render.camera (its keys, path and orbit) after the domain, refusing
// keys of the other dimension, a camera looking at its own position, and
// keyframes out of order, each naming its key.
void read_camera(FieldReader& r, Scene& s);
// render.camera as read_camera reads it back.
json write_camera(const Scene::Render::Camera& camera, int dimension);
const KeyTable<Scene::Render::Surface>& surface_keys();
// output_keys.cpp
const KeyTable<Scene::Output>& output_keys();

// effects.obstacles (sph/boundaries/obstacle_keys.cpp), with each mesh's OBJ
// file read here, relative to the scene file's folder.
std::vector<SceneObstacle> read_obstacles(FieldReader& r, int dim, const std::string& file);
// Checks obstacle i against the domain and the spacing (obstacle_keys.cpp).
// Returns an upper bound on the boundary particles its shell takes.
double check_obstacle(const FieldReader& r, const Scene& s, std::size_t i, double layers);

// Checks paddle i (paddle_keys.cpp): its box at rest, and the room its motion
// sweeps over the clip inside the domain. Returns the boundary particles of
// its shell.
double check_paddle(const FieldReader& r, const Scene& s, std::size_t i, double layers);

} // namespace sph
