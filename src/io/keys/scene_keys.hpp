#pragma once
// The key tables of the scene's own objects (the solver's and the effects'
// are in their files under sph/), and the readers of the key families that
// are lists of shapes (obstacles, emitters, paddles), which are not yet
// tables. The scene reads and writes itself from these (io/scene.cpp).

#include "io/field_reader.hpp"
#include "io/scene.hpp"

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
// output_keys.cpp
const KeyTable<Scene::Output>& output_keys();

// effects.obstacles (obstacle_keys.cpp): each element a box, a sphere or (3D)
// a mesh, whose OBJ file is read here relative to the scene file's folder.
// With no list the keys are still read, for the documentation.
void read_obstacles(FieldReader& r, int dim, const std::string& file,
                    std::vector<SceneObstacle>& obstacles);
json write_obstacles(const std::vector<SceneObstacle>& obstacles, int dim);
// Checks obstacle i against the domain and the spacing. Returns an upper
// bound on the boundary particles its shell takes (sph/obstacles.cpp).
double check_obstacle(const FieldReader& r, const Scene& s, std::size_t i, double layers);

// effects.emitters (emitter_keys.cpp): each a box, a velocity and a time window.
void read_emitters(FieldReader& r, int dim, std::vector<SceneEmitter>& emitters);
json write_emitters(const std::vector<SceneEmitter>& emitters, int dim);

// effects.paddles (paddle_keys.cpp): each a box with a prescribed motion.
void read_paddles(FieldReader& r, int dim, std::vector<ScenePaddle>& paddles);
json write_paddles(const std::vector<ScenePaddle>& paddles, int dim);
// Checks paddle i: its box at rest, and the room its motion sweeps over the
// clip inside the domain. Returns the boundary particles of its shell.
double check_paddle(const FieldReader& r, const Scene& s, std::size_t i, double layers);

} // namespace sph
