#pragma once
// The colour field carried from the particles to a surface's vertices: at
// each vertex the SPH average sum_j c_j W_j / sum_j W_j over the particles
// within `support` (W the poly6 shape (1 - r^2/h^2)^3, Mueller et al. 2003,
// "Particle-based fluid simulation for interactive applications", eq. 20,
// normalised by the sum, so the same for 2D and 3D), found through a uniform
// grid of cells `support` wide. A vertex with no particle that close takes
// its nearest particle's value within the 27 (9) cells around it, else the
// frame's lowest.

#include "render/surface/surface_mesh.hpp"
#include "sph/snapshot.hpp"

#include <vector>

namespace sph {

void colour_vertices(SurfaceMesh& mesh, const Snapshot& frame, const std::vector<float>& scalars,
                     double support);

} // namespace sph
