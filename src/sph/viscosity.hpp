#pragma once
// Viscous accelerations of the wcsph and dfsph solvers (the seed's viscosity
// is part of its pair force). Both add to state.acceleration.

#include "sph/boundary_particles.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

// Laminar viscosity of a Newtonian fluid with dynamic viscosity mu (Morris,
// Fox & Zhu 1997, eq. 8, Brookshaw's second derivative):
//   a_i += sum_j m (2 mu) / (rho_i rho_j) (x_ij . grad W_ij) / (r^2 + 0.01 h^2) v_ij
// The walls are at rest and no-slip: a wall particle counts as fluid of
// density rho0, mass rho0 V_b and velocity 0.
template <int D, class Kernel>
void add_laminar_viscosity(const Params<D>& params, const Kernel& kernel,
                           const NeighbourList& neighbours, const BoundaryParticles<D>* boundary,
                           const NeighbourList& boundary_neighbours, State<D>& state) {
    const std::size_t n = state.size();
    const Real eps = 0.01 * params.h * params.h;
    const Real two_mu = 2 * params.viscosity;
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D> a(0);
        for (std::uint32_t j : neighbours.of(i)) {
            const Vec<D> x_ij = state.position[i] - state.position[j];
            const Real r2 = squared_length<D>(x_ij);
            const Real r = std::sqrt(r2);
            // x . grad W = r dW/dr: no direction needed, fine at r = 0.
            const Real x_dot_grad = r * kernel.dW(r);
            a += (params.mass / state.density[j] * x_dot_grad / (r2 + eps)) *
                 (state.velocity[i] - state.velocity[j]);
        }
        if (boundary) {
            const auto xb = boundary->positions();
            const auto volume = boundary->volumes();
            for (std::uint32_t b : boundary_neighbours.of(i)) {
                const Vec<D> x_ib = state.position[i] - xb[b];
                const Real r2 = squared_length<D>(x_ib);
                const Real r = std::sqrt(r2);
                a += (volume[b] * r * kernel.dW(r) / (r2 + eps)) * state.velocity[i];
            }
        }
        state.acceleration[i] += (two_mu / state.density[i]) * a;
    }
}

// Monaghan's artificial viscosity (Monaghan 1992, eq. 4.1, without the
// quadratic beta term), acting only between approaching particles:
//   Pi_ij = -(2 alpha h c / (rho_i + rho_j)) (v_ij . x_ij) / (r^2 + 0.01 h^2)  if v_ij . x_ij < 0
//   a_i -= sum_j m Pi_ij grad W_ij
// with h the support radius. It damps the noise a weakly compressible fluid
// rings with, at the price of some extra dissipation.
template <int D, class Kernel>
void add_artificial_viscosity(const Params<D>& params, const Kernel& kernel,
                              const NeighbourList& neighbours, const BoundaryParticles<D>* boundary,
                              const NeighbourList& boundary_neighbours, State<D>& state) {
    const std::size_t n = state.size();
    const Real eps = 0.01 * params.h * params.h;
    const Real nu_scale = 2 * params.artificial_viscosity * params.h * params.sound_speed();
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D> a(0);
        for (std::uint32_t j : neighbours.of(i)) {
            const Vec<D> x_ij = state.position[i] - state.position[j];
            const Real v_dot_x = glm::dot(state.velocity[i] - state.velocity[j], x_ij);
            if (v_dot_x >= 0)
                continue;
            const Real r2 = squared_length<D>(x_ij);
            const Real r = std::sqrt(r2);
            const Real Pi =
                -nu_scale / (state.density[i] + state.density[j]) * v_dot_x / (r2 + eps);
            // grad W = (dW/dr / r) x_ij; at r = 0 v_dot_x is 0 and we never get here.
            a -= (params.mass * Pi * kernel.dW(r) / r) * x_ij;
        }
        // The walls too (as Akinci et al. 2012 do): a wall particle is fluid
        // at rest with the particle's density and mass rho0 V_b. Without it a
        // particle that comes close to a wall, where the smooth kernels'
        // gradients fade, meets no damping and squirts along it.
        if (boundary) {
            const auto xb = boundary->positions();
            const auto volume = boundary->volumes();
            for (std::uint32_t b : boundary_neighbours.of(i)) {
                const Vec<D> x_ib = state.position[i] - xb[b];
                const Real v_dot_x = glm::dot(state.velocity[i], x_ib);
                if (v_dot_x >= 0)
                    continue;
                const Real r2 = squared_length<D>(x_ib);
                const Real r = std::sqrt(r2);
                const Real Pi = -nu_scale / (2 * state.density[i]) * v_dot_x / (r2 + eps);
                a -= (params.rest_density * volume[b] * Pi * kernel.dW(r) / r) * x_ib;
            }
        }
        state.acceleration[i] += a;
    }
}

} // namespace sph
