#pragma once
// Time integration of velocities and positions from the accelerations, as
// the two half-operations every scheme is built from.

#include "sph/params.hpp"
#include "sph/state.hpp"

namespace sph {

// v += dt a
template <int D>
void kick(Real dt, State<D>& state) {
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        state.velocity[i] += dt * state.acceleration[i];
}

// x += dt v
template <int D>
void drift(Real dt, State<D>& state) {
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        state.position[i] += dt * state.velocity[i];
}

// Symplectic (semi-implicit) Euler, the seed's scheme: the new velocity moves
// the particle, v += dt a, then x += dt v.
template <int D>
void integrate_symplectic_euler(Real dt, State<D>& state) {
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        state.velocity[i] += dt * state.acceleration[i];
        state.position[i] += dt * state.velocity[i];
    }
}

} // namespace sph
