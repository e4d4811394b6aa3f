#pragma once
// The scene's boundaries, built once when a simulation starts: the list the
// last guard walks (boundary.hpp) and the one set of boundary particles the
// solvers sum over (boundary_particles.hpp).

#include "sph/boundaries/boundary.hpp"
#include "sph/params.hpp"

#include <optional>

namespace sph {

// The box's walls, then the obstacles and the paddles when the scene has
// them: the order the last guard puts particles back in.
template <int D>
BoundaryList<D> make_boundaries(const Params<D>& params);

// The obstacles' shells, then the domain walls' particles when
// params.walls asks for them, as static particles; the paddles' shells
// after them as the moving ones. None when there is none of these. With a
// `region`, only the static particles inside it (a process's over MPI
// ranks, parallel/rank_partition.cpp), which find the same neighbours in
// the same order as the whole set for a point whose support lies inside.
template <int D>
std::optional<BoundaryParticles<D>> make_boundary_particles(const Params<D>& params,
                                                            const Box<D>* region = nullptr);
// The obstacles' shells, sampled (sph/boundaries/obstacles.hpp).
template <int D>
BoundarySamples<D> obstacle_shells(const Params<D>& params);

// The static particles alone (make_boundary_particles without the paddles);
// the obstacles' `shells` when sampled already (laid again by region over
// MPI ranks, a mesh is not sampled again each time).
template <int D>
std::optional<BoundaryParticles<D>>
make_static_boundary_particles(const Params<D>& params, const Box<D>* region = nullptr,
                               const BoundarySamples<D>* shells = nullptr);

} // namespace sph
