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
// the hydrostatic pressure. With solver.wall_pressure extrapolated the wall
// particle has a pressure and density of its own (sph/wall_pressure.hpp):
//   a_i -= sum_b rho0 V_b (p_i / rho_i^2 + p_b / rho_b^2) grad W_ib
// and with solver.wall_pressure hydrostatic it takes the fluid particle's
// density and p_b = max(p_i + rho_i g . (x_b - x_i), 0) (sph/params.hpp).
// The viscosities the scene names join the same pass, which shares among
// them the gathers of the neighbour's position, velocity and density, r and
// the kernel's derivative (one pass over the pairs instead of up to three):
// Monaghan's artificial viscosity adds its Pi_ij to the pair's pressure terms
// (Monaghan 1992, eq. 3.3 with 4.1; sph/effects/artificial_viscosity.hpp),
// Morris's laminar viscosity its own term along v_ij
// (sph/effects/laminar_viscosity.hpp).
// Overwrites state.acceleration: it is the first force of the step.
// p / rho^2 is computed once per particle into `pressure_term` (the caller's
// scratch, kept between steps), not once per pair: a division per pair was a
// fifth of the loop's time.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/effects/artificial_viscosity.hpp"
#include "sph/effects/laminar_viscosity.hpp"
#include "sph/headroom.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/pair_direction.hpp"
#include "sph/params.hpp"
#include "sph/vector_clones.hpp"

#include <type_traits>
#include <vector>

namespace sph {

// The viscosities that join the pressure pass; null: not in this scene.
struct PairViscosities {
    const MonaghanViscosity* artificial = nullptr;
    const MorrisViscosity* laminar = nullptr;

    // Calls pass(artificial, laminar) with a std::bool_constant for each,
    // so that a pass compiled for each set has no test in its loops.
    template <class Pass>
    void dispatch(Pass&& pass) const {
        const auto with_laminar = [&](auto has_artificial) {
            if (laminar)
                pass(has_artificial, std::true_type{});
            else
                pass(has_artificial, std::false_type{});
        };
        if (artificial)
            with_laminar(std::true_type{});
        else
            with_laminar(std::false_type{});
    }
};

namespace detail {

// The pass over the pairs, compiled for each set of viscosities and wall
// pressure: a test in the wall loop keeps it from vectorising, which also
// changes its sum's order (and so every bit of a 3D run). A function of its
// own, not a lambda, so that its OpenMP region is cloned with it
// (sph/vector_clones.hpp).
template <bool artificial, bool laminar, bool hydrostatic, bool extrapolated, int D, class Kernel>
SPHCLIP_CLONED void
accelerate_pairs(const Params<D>& params, const Kernel& kernel, const NeighbourList& neighbours,
                 const BoundaryParticles<D>* boundary, const NeighbourList& boundary_neighbours,
                 const PairViscosities& viscosities, const std::vector<Real>& pressure_term,
                 State<D>& state, const Real* wall_pressure_term) {
    const std::size_t n = state.size();
    const MonaghanViscosity Pi = artificial ? *viscosities.artificial : MonaghanViscosity{};
    const MorrisViscosity morris = laminar ? *viscosities.laminar : MorrisViscosity{};
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        const Real pi_over_rho2 = pressure_term[i];
        const Real viscous_scale = laminar ? morris.two_mu / state.density[i] : 0;
        Vec<D> a = sum_over_neighbours(neighbours, i, [&](std::uint32_t j) {
            const Vec<D> x_ij = state.position[i] - state.position[j];
            const Real r2 = squared_length<D>(x_ij);
            const Real r = std::sqrt(r2);
            const Vec<D> v_ij = state.velocity[i] - state.velocity[j];
            Real factor = pi_over_rho2 + pressure_term[j];
            if constexpr (artificial)
                factor += Pi(glm::dot(v_ij, x_ij), state.density[i] + state.density[j], r2);
            if constexpr (Kernel::smooth_at_origin) {
                // grad W = (dW/dr / r) x: one factor for both terms.
                const Real f = kernel.dW_over_r(r);
                Vec<D> term = -(params.mass * factor * f) * x_ij;
                if constexpr (laminar)
                    term += (viscous_scale *
                             morris.fluid_from_factor(params.mass, state.density[j], r2, f)) *
                            v_ij;
                return term;
            } else {
                Vec<D> term = -(params.mass * factor) * pair_gradient(kernel, state, i, j, x_ij, r);
                if constexpr (laminar)
                    term += (viscous_scale *
                             morris.fluid(kernel, params.mass, state.density[j], r, r2)) *
                            v_ij;
                return term;
            }
        });
        if (boundary) {
            const auto xb = boundary->positions();
            const auto volume = boundary->volumes();
            // A local span, not boundary->velocity(b): the loop then vectorises.
            const auto wall_velocity = boundary->velocities();
            a += sum_over_neighbours(boundary_neighbours, i, [&](std::uint32_t b) {
                const Vec<D> x_ib = state.position[i] - xb[b];
                const Real r2 = squared_length<D>(x_ib);
                const Real r = std::sqrt(r2);
                const Vec<D> v_ib = state.velocity[i] - wall_velocity[b];
                Real factor = 2 * pi_over_rho2;
                if constexpr (extrapolated)
                    factor = pi_over_rho2 + wall_pressure_term[b];
                // (p_i + p_b) / rho_i^2 with the wall's hydrostatic rise,
                // p_b = max(p_i + rho_i g . (x_b - x_i), 0).
                else if constexpr (hydrostatic)
                    factor =
                        pi_over_rho2 + std::max(pi_over_rho2 - glm::dot(params.wall_gravity, x_ib) /
                                                                   state.density[i],
                                                Real(0));
                if constexpr (artificial)
                    factor += Pi(glm::dot(v_ib, x_ib), 2 * state.density[i], r2);
                Vec<D> term = -(params.rest_density * volume[b] * factor) *
                              boundary_gradient(kernel, x_ib, r);
                if constexpr (laminar)
                    term += (viscous_scale * morris.wall(kernel, volume[b], r, r2)) * v_ib;
                return term;
            });
        }
        state.acceleration[i] = a;
    }
}

} // namespace detail

template <int D, class Kernel>
void compute_pressure_acceleration(const Params<D>& params, const Kernel& kernel,
                                   const NeighbourList& neighbours,
                                   const BoundaryParticles<D>* boundary,
                                   const NeighbourList& boundary_neighbours,
                                   const PairViscosities& viscosities,
                                   std::vector<Real>& pressure_term, State<D>& state,
                                   const Real* wall_pressure_term = nullptr) {
    const std::size_t n = state.size();
    resize_with_headroom(pressure_term, n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        pressure_term[i] = state.pressure[i] / (state.density[i] * state.density[i]);
    const bool hydrostatic_walls = params.wall_gravity != Vec<D>(0);
    // solver.wall_pressure extrapolated: p_b / rho_b^2 per wall particle
    // (sph/wall_pressure.hpp), which replaces the mirrored p_i / rho_i^2.
    const bool extrapolated_walls = wall_pressure_term != nullptr;
    const auto accelerate = [&](auto artificial, auto laminar, auto hydrostatic,
                                auto extrapolated) {
        detail::accelerate_pairs<decltype(artificial)::value, decltype(laminar)::value,
                                 decltype(hydrostatic)::value, decltype(extrapolated)::value>(
            params, kernel, neighbours, boundary, boundary_neighbours, viscosities, pressure_term,
            state, wall_pressure_term);
    };
    viscosities.dispatch([&](auto artificial, auto laminar) {
        if (extrapolated_walls)
            accelerate(artificial, laminar, std::false_type{}, std::true_type{});
        else if (hydrostatic_walls)
            accelerate(artificial, laminar, std::true_type{}, std::false_type{});
        else
            accelerate(artificial, laminar, std::false_type{}, std::false_type{});
    });
}

// The viscosities' wall terms alone, for dfsph (its pressure comes from its
// solves; it sums the fluid pairs' terms in its own layout, in floats), from
// the walls' gradients its density pass keeps, w_ib = rho0 V_b grad W_ib per
// pair of `walls`: no kernel evaluated again. With a wall particle of density
// rho0 and mass rho0 V_b, the terms above become
//   Monaghan: -rho0 V_b Pi_ib grad W_ib = -Pi_ib w_ib,
//   Morris: (2 mu / rho_i) V_b (x_ib . grad W_ib) / (r^2 + eps) v_ib,
// with V_b x_ib . grad W_ib = x_ib . w_ib / rho0. Overwrites state.acceleration.
template <bool artificial, bool laminar, int D>
SPHCLIP_CLONED void
set_wall_viscosities(const Params<D>& params, const PairViscosities& viscosities,
                     const BoundaryParticles<D>& boundary, const NeighbourList& walls,
                     const std::vector<Vec<D>>& wall_gradient, State<D>& state) {
    const std::size_t n = state.size();
    const MonaghanViscosity Pi = artificial ? *viscosities.artificial : MonaghanViscosity{};
    const MorrisViscosity morris = laminar ? *viscosities.laminar : MorrisViscosity{};
    const auto xb = boundary.positions();
    // A local span, not boundary.velocity(b): the loop then vectorises.
    const auto wall_velocity = boundary.velocities();
    const Real rho0 = params.rest_density;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        const Vec<D> x_i = state.position[i], v_i = state.velocity[i];
        const Real rho_i = state.density[i];
        const Real viscous_scale = laminar ? morris.two_mu / (rho_i * rho0) : 0;
        state.acceleration[i] = sum_over_pairs(walls, i, [&](std::size_t e, std::uint32_t b) {
            const Vec<D> x_ib = x_i - xb[b];
            const Vec<D> v_ib = v_i - wall_velocity[b];
            const Real r2 = squared_length<D>(x_ib);
            Vec<D> term(0);
            if constexpr (artificial)
                term = -Pi(glm::dot(v_ib, x_ib), 2 * rho_i, r2) * wall_gradient[e];
            if constexpr (laminar)
                term +=
                    (viscous_scale * glm::dot(x_ib, wall_gradient[e]) / (r2 + morris.eps)) * v_ib;
            return term;
        });
    }
}

} // namespace sph
