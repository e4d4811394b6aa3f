#pragma once
// The walls' pressure extrapolated from the fluid (solver.wall_pressure =
// extrapolated, wcsph): Adami, Hu & Adams 2012, "A generalized wall boundary
// condition for smoothed particle hydrodynamics", J. Comput. Phys. 231,
// eq. 27, for walls at rest:
//   p_b = (sum_f p_f W_bf + g . sum_f rho_f (x_b - x_f) W_bf) / sum_f W_bf
// a Shepard average of the fluid's pressure around the wall particle plus
// the weight of the fluid between, and its density from the equation of
// state, rho_b = rho0 (1 + p_b / B)^(1/7) (their eq. 28 for Tait's law).
// Where the mirrored walls give each fluid particle its own pressure back,
// these give every particle beside a wall particle the same one, so a thin
// layer (the surge's tip) feels the pressure of the fluid that pushes it,
// and the corner of a column at rest the pressure of the column above.
// No tension: p_b is clamped at 0 as the fluid's is.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/headroom.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace sph {

// Per wall particle, kept between steps to reuse their memory.
struct WallPressureScratch {
    std::vector<Real> pressure_term;  // p_b / rho_b^2, what the force reads, Pa m^6/kg^2
    std::vector<std::uint32_t> start; // where each wall particle's fluid pairs begin in `fluid`
    std::vector<std::uint32_t> fluid; // the boundary list reversed
    std::vector<std::uint32_t> fill;  // scratch of the reversal
};

// scratch.pressure_term[b] = p_b / rho_b^2 from the fluid's pressures and
// densities, through the fluid-to-wall list `boundary_neighbours`. The list
// is reversed by a counting sort in particle order, so the sums' order, and
// every bit of the result, is the same with any thread count.
template <int D, class Kernel>
void extrapolate_wall_pressure(const Params<D>& params, const Kernel& kernel,
                               const BoundaryParticles<D>& boundary,
                               const NeighbourList& boundary_neighbours, const State<D>& state,
                               WallPressureScratch& scratch) {
    const std::size_t walls = boundary.size();
    const std::size_t n = state.size();
    const auto xb = boundary.positions();
    scratch.start.assign(walls + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t e = boundary_neighbours.start[i]; e < boundary_neighbours.start[i + 1];
             ++e)
            ++scratch.start[boundary_neighbours.index[e] + 1];
    for (std::size_t b = 0; b < walls; ++b)
        scratch.start[b + 1] += scratch.start[b];
    const std::size_t pairs = scratch.start[walls];
    resize_with_headroom(scratch.fluid, pairs);
    scratch.fill.assign(scratch.start.begin(), scratch.start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t e = boundary_neighbours.start[i]; e < boundary_neighbours.start[i + 1];
             ++e)
            scratch.fluid[scratch.fill[boundary_neighbours.index[e]]++] = std::uint32_t(i);
    resize_with_headroom(scratch.pressure_term, walls);
    const Vec<D> g = params.wall_gravity;
    const Real B = params.bulk_modulus / 7;
    const Real rho0 = params.rest_density;
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t b = 0; b < walls; ++b) {
        Real weight = 0, sum = 0;
        for (std::size_t k = scratch.start[b]; k < scratch.start[b + 1]; ++k) {
            const std::uint32_t f = scratch.fluid[k];
            const Vec<D> x_bf = xb[b] - state.position[f];
            const Real W = kernel.W(std::sqrt(squared_length<D>(x_bf)));
            weight += W;
            sum += W * (state.pressure[f] + state.density[f] * glm::dot(g, x_bf));
        }
        const Real p = weight > 0 ? std::max(sum / weight, Real(0)) : 0;
        const Real rho = rho0 * std::pow(1 + p / B, Real(1) / 7);
        scratch.pressure_term[b] = p / (rho * rho);
    }
}

} // namespace sph
