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
// after them as the moving ones. None when there is none of these.
template <int D>
std::optional<BoundaryParticles<D>> make_boundary_particles(const Params<D>& params);

} // namespace sph
