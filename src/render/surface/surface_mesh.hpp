#pragma once
// The fluid's free surface as a triangle mesh, reconstructed from a frame's
// particles (reconstruct.hpp), drawn by SurfacePass and exported as .ply.
// 3D: the zero level set of a narrow-band signed distance (OpenVDB). 2D: the
// filled region inside the fluid's outline, and the outline itself.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace sph {

// How the surface is made from the particles (scene keys render.surface.*,
// docs/rendering.md, "Surface"). Lengths relative to the particle spacing.
struct SurfaceSettings {
    double voxel = 0.5;  // grid cell, x spacing
    double radius = 1.0; // 3D: each particle's sphere; 2D: half the kernel's support; x spacing
    int smoothing = 2;   // smoothing passes over the level set (3D) or the grid (2D)
};

struct SurfaceMesh {
    int dimension = 3;
    // Per vertex: x, y, z (m, world), the normal (unit, pointing out of the
    // fluid; 2D: +z) and the colour field's value there.
    std::vector<float> positions, normals;
    std::vector<float> scalar;
    std::vector<std::uint32_t> triangles; // three vertex indices each
    // 2D: the outline as segments, two vertex indices each (empty in 3D).
    std::vector<std::uint32_t> outline;

    std::size_t vertices() const { return scalar.size(); }
};

// The level set a 3D surface was extracted from (OpenVDB's FloatGrid), kept
// for the .vdb export; opaque so that only one file needs OpenVDB's headers.
class LevelSet;

// Where a 3D reconstruction's time goes (the surface benchmark's breakdown),
// s; together they make its reconstruction_seconds.
struct SurfaceSteps {
    double rasterise = 0; // the particles' spheres into the level set
    double smoothing = 0; // the smoothing passes (and the erosion without them)
    double meshing = 0;   // the level's crossing to triangles
    double normals = 0;   // the vertices' normals from the gradient
};

struct Surface {
    SurfaceMesh mesh;
    std::shared_ptr<const LevelSet> level_set; // 3D only
    double reconstruction_seconds = 0;         // particles to level set to mesh
    double colour_seconds = 0;                 // the colour field at the vertices
    SurfaceSteps steps;                        // 3D
};

} // namespace sph
