#pragma once
// Particles to a surface mesh. 3D (OpenVDB, level_set_vdb.cpp): each
// particle rasterised as a sphere of radius r into a narrow-band level set
// (openvdb::tools::ParticlesToLevelSet, the union of the spheres: Zhu and
// Bridson 2005, "Animating sand as a fluid", sec. 4, in its simplest form),
// smoothed by Gaussian passes, then meshed (openvdb::tools::volumeToMesh) at
// the level -(r - spacing / 2), an erosion by that much, so that the surface
// lies where the drawn spheres' would (dilate, smooth, erode: the gaps
// between particles closed, the bumps of single spheres gone). 2D (marching_squares.cpp):
// a kernel sum on a grid, its half-full level traced by marching squares and
// filled. The colour field is then carried from the particles to the
// vertices (vertex_colours.hpp).

#include "render/surface/surface_mesh.hpp"
#include "scene/render_choices.hpp"
#include "sph/snapshot.hpp"

#include <filesystem>
#include <string_view>

namespace sph {

// Whether this build can reconstruct a 3D surface (OpenVDB found at build
// time; -DSPHCLIP_OPENVDB=OFF turns it off; its module loaded: this loads
// it). 2D needs nothing.
bool surface_3d_available();
// Why not, or "" when it can.
std::string surface_3d_unavailable_reason();

// The scalar each particle is coloured by: `field` velocity (the speed),
// density or pressure, as the spheres are.
std::vector<float> particle_scalars(const Snapshot& frame, ColourField field);

// The frame's surface, coloured by `field`; `spacing` the particle spacing
// (m). Throws std::runtime_error for a 3D frame where surface_3d_available()
// is false.
Surface reconstruct_surface(const Snapshot& frame, ColourField field, double spacing,
                            const SurfaceSettings& settings);

// 3D only (level_set_vdb.cpp): the level set's narrow band, and the mesh of
// its zero crossing with normals from its gradient; no colour yet. `steps`,
// if given, gets the time of each step.
std::shared_ptr<const LevelSet> make_level_set(const Snapshot& frame, double spacing,
                                               const SurfaceSettings& settings,
                                               SurfaceSteps* steps = nullptr);
SurfaceMesh mesh_level_set(const LevelSet& level_set, SurfaceSteps* steps = nullptr);

// 2D only (marching_squares.cpp): the filled region and its outline, with
// the colour field interpolated from the grid.
SurfaceMesh reconstruct_region_2d(const Snapshot& frame, const std::vector<float>& scalars,
                                  double spacing, const SurfaceSettings& settings);

// Writes the level set to `path` as an OpenVDB file (one grid named
// "surface"), through a temporary: a reader sees no half-written file.
void write_level_set(const LevelSet& level_set, const std::filesystem::path& path);

} // namespace sph
