#pragma once
// The first stage the wall-aware solvers (wcsph, dfsph) share: neighbours at
// the current positions, then the density by summation over fluid and wall
// particles (Akinci et al. 2012, eq. 6).

#include "sph/density.hpp"
#include "sph/solvers/solver.hpp"

namespace sph {

template <int D, class Kernel>
void find_neighbours_and_density(const Params<D>& params, const Kernel& kernel,
                                 StepContext<D>& context, State<D>& state) {
    context.find_neighbours(state.position, params.h);
    auto timed = context.time(Stage::density);
    compute_density(params, kernel, context.neighbours, state);
    if (context.boundary)
        add_boundary_density(params, kernel, *context.boundary, context.boundary_neighbours, state);
}

} // namespace sph
