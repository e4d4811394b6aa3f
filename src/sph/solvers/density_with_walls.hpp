#pragma once
// The first stage the wall-aware solvers (wcsph, dfsph) share: neighbours at
// the current positions, then the density by summation over fluid and wall
// particles (Akinci et al. 2012, eq. 6), or the carried density's start.

#include "sph/density.hpp"
#include "sph/solvers/solver.hpp"

#include <algorithm>
#include <vector>

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

// The carried density (wcsph's solver.density_diffusion, dfsph's
// solver.density = carried): the neighbours, and the
// density of particles that have none yet (the start, an emitter's new
// ones: density 0) from the summation, but not below rho0, which a particle
// at a free surface sums to for want of neighbours. The solver's step
// advances it.
template <int D, class Kernel>
void find_neighbours_and_carried_density(const Params<D>& params, const Kernel& kernel,
                                         StepContext<D>& context, State<D>& state) {
    context.find_neighbours(state.position, params.h);
    const std::size_t n = state.size();
    if (std::any_of(state.density.begin(), state.density.end(),
                    [](Real rho) { return rho <= 0; })) {
        auto timed = context.time(Stage::density);
        std::vector<Real> carried = state.density;
        compute_density(params, kernel, context.neighbours, state);
        if (context.boundary)
            add_boundary_density(params, kernel, *context.boundary, context.boundary_neighbours,
                                 state);
        for (std::size_t i = 0; i < n; ++i)
            state.density[i] =
                carried[i] > 0 ? carried[i] : std::max(state.density[i], params.rest_density);
    }
}

} // namespace sph
