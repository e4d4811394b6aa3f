#pragma once
// Pressure acceleration of the weakly compressible solvers, in the symmetric
// form that conserves momentum (Monaghan 1992, eq. 3.3; Becker & Teschner
// 2007, eq. 6):
//   a_i = - sum_j m (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij
// and from the wall particles, whose pressure and density are mirrored from
// the fluid particle beside them (p_b = p_i, rho_b = rho_i):
//   a_i -= sum_b rho0 V_b (2 p_i / rho_i^2) grad W_ib
// Our walls are several full layers of fluid-like particles, so they must
// hold the fluid up as fluid below would; Akinci et al. 2012's single term
// p_i / rho_i^2 (eq. 10, for one layer) would leave the bottom layer at twice
// the hydrostatic pressure.
// With Monaghan's artificial viscosity given (sph/effects/artificial_viscosity.hpp),
// its Pi_ij joins the pressure terms of the same pair, as in Monaghan 1992,
// eq. 3.3 with 4.1: one pass over the pairs instead of two, sharing the
// gathers of the neighbour's position and density, r and grad W.
// Overwrites state.acceleration: it is the first force of the step.
// p / rho^2 is computed once per particle into `pressure_term` (the caller's
// scratch, kept between steps), not once per pair: a division per pair was a
// fifth of the loop's time.

#include "sph/boundary_particles.hpp"
#include "sph/effects/artificial_viscosity.hpp"
#include "sph/headroom.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/pair_direction.hpp"
#include "sph/params.hpp"

#include <type_traits>
#include <vector>

namespace sph {

template <int D, class Kernel>
void compute_pressure_acceleration(const Params<D>& params, const Kernel& kernel,
                                   const NeighbourList& neighbours,
                                   const BoundaryParticles<D>* boundary,
                                   const NeighbourList& boundary_neighbours,
                                   const MonaghanViscosity* viscosity,
                                   std::vector<Real>& pressure_term, State<D>& state) {
    const std::size_t n = state.size();
    resize_with_headroom(pressure_term, n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        pressure_term[i] = state.pressure[i] / (state.density[i] * state.density[i]);
    // Compiled with and without the viscosity, so neither loop tests for it.
    const auto accelerate = [&](auto with_viscosity) {
        constexpr bool viscous = decltype(with_viscosity)::value;
        const MonaghanViscosity Pi = viscous ? *viscosity : MonaghanViscosity{};
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            const Real pi_over_rho2 = pressure_term[i];
            Vec<D> a = -sum_over_neighbours(neighbours, i, [&](std::uint32_t j) {
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r2 = squared_length<D>(x_ij);
                const Real r = std::sqrt(r2);
                Real factor = pi_over_rho2 + pressure_term[j];
                if constexpr (viscous)
                    factor += Pi(glm::dot(state.velocity[i] - state.velocity[j], x_ij),
                                 state.density[i] + state.density[j], r2);
                return (params.mass * factor) * pair_gradient(kernel, state, i, j, x_ij, r);
            });
            if (boundary) {
                const auto xb = boundary->positions();
                const auto volume = boundary->volumes();
                // A local span, not boundary->velocity(b): the loop then vectorises.
                const auto wall_velocity = boundary->velocities();
                a -= sum_over_neighbours(boundary_neighbours, i, [&](std::uint32_t b) {
                    const Vec<D> x_ib = state.position[i] - xb[b];
                    const Real r2 = squared_length<D>(x_ib);
                    const Real r = std::sqrt(r2);
                    Real factor = 2 * pi_over_rho2;
                    if constexpr (viscous)
                        factor += Pi(glm::dot(state.velocity[i] - wall_velocity[b], x_ib),
                                     2 * state.density[i], r2);
                    return (params.rest_density * volume[b] * factor) *
                           boundary_gradient(kernel, x_ib, r);
                });
            }
            state.acceleration[i] = a;
        }
    };
    if (viscosity)
        accelerate(std::true_type{});
    else
        accelerate(std::false_type{});
}

} // namespace sph
