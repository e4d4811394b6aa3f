#pragma once
// Time integration of velocities and positions from the accelerations.

#include "sph/params.hpp"
#include "sph/state.hpp"

namespace sph {

// Symplectic (semi-implicit) Euler, the seed's scheme: the new velocity moves
// the particle, v += dt a, then x += dt v.
template <int D>
void integrate_symplectic_euler(const Params<D>& params, State<D>& state) {
    const std::size_t n = state.size();
    const Real dt = params.dt;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        state.velocity[i] += dt * state.acceleration[i];
        state.position[i] += dt * state.velocity[i];
    }
}

} // namespace sph
