#pragma once
// The density by the continuity equation with delta-SPH's diffusive term
// (solver.density_diffusion, wcsph): instead of summing the kernel over the
// neighbours, each particle carries its density and changes it at the rate
//   D rho_i / Dt = sum_j m v_ij . grad W_ij + sum_b rho0 V_b v_ib . grad W_ib
//                + delta l c0 sum_j (m / rho_j) psi_ij . grad W_ij
// (Monaghan 1992, eq. 2.21, with the walls as in Akinci et al. 2012), the last
// term that of Antuono, Colagrossi, Marrone & Molteni 2010 ("Free-surface
// flows solved by means of SPH schemes with numerical diffusive terms",
// Comput. Phys. Commun. 181, eq. 10):
//   psi_ij = 2 (rho_j - rho_i) x_ji / |x_ji|^2 - (<grad rho>_i^L + <grad rho>_j^L)
// with the renormalised density gradient (Randles & Libersky 1996)
//   <grad rho>_i^L = L_i sum_j (rho_j - rho_i) grad W_ij V_j,
//   L_i = [sum_j V_j grad W_ij (x_j - x_i)^T]^-1.
// The gradient term takes out the part of the Molteni & Colagrossi 2009
// term that a smooth density (the hydrostatic one) would feed, so the term
// diffuses only the noise and is consistent to first order. l is the
// smoothing length, half our support radius h. Only fluid pairs diffuse: a
// wall particle carries no density of its own.
// Summed density is low at a free surface (missing neighbours); a carried
// density is not, which is why weakly compressible codes that resolve thin
// layers (DualSPHysics, Crespo et al. 2015) carry it.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/headroom.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/pair_direction.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"
#include "sph/vector_clones.hpp"

#include <cmath>
#include <vector>

namespace sph {

namespace detail {

// The inverse of L^-1 = sum_j V_j grad W_ij (x_j - x_i)^T, or the identity
// (the plain sum, Molteni & Colagrossi's gradient) when it is nearly
// singular. It is the identity inside the fluid; its determinant is about
// 1/2^D at a flat free surface and 1/16 at the corner of a 2D block. Below
// a hundredth the neighbours lie nearly on a line (a tip or a jet one
// particle thick, a drop) and the fitted gradient is noise.
template <int D>
glm::mat<D, D, Real> renormalisation_inverse(const glm::mat<D, D, Real>& A) {
    const Real det = glm::determinant(A);
    if (!(std::abs(det) > Real(0.01)))
        return glm::mat<D, D, Real>(1);
    return glm::inverse(A);
}

} // namespace detail

template <int D>
struct ContinuityScratch {
    std::vector<Vec<D>> density_gradient; // <grad rho>_i^L, kg/m^(D+1)
};

// rate[i] = D rho_i / Dt at the current positions, velocities and carried
// densities; `delta` 0 leaves the diffusive term (and its gradient pass) out.
template <int D, class Kernel>
SPHCLIP_CLONED void
compute_density_rate(const Params<D>& params, const Kernel& kernel, const NeighbourList& neighbours,
                     const BoundaryParticles<D>* boundary, const NeighbourList& boundary_neighbours,
                     const State<D>& state, ContinuityScratch<D>& scratch,
                     std::vector<Real>& rate) {
    const std::size_t n = state.size();
    resize_with_headroom(rate, n);
    const Real delta = params.density_diffusion;
    std::vector<Vec<D>>& gradient = scratch.density_gradient;
    if (delta > 0) {
        resize_with_headroom(gradient, n);
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            glm::mat<D, D, Real> A(0);
            Vec<D> g(0);
            for (std::size_t e = neighbours.start[i]; e < neighbours.start[i + 1]; ++e) {
                const std::uint32_t j = neighbours.index[e];
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r = std::sqrt(squared_length<D>(x_ij));
                const Vec<D> grad =
                    (params.mass / state.density[j]) * pair_gradient(kernel, state, i, j, x_ij, r);
                // grad W_ij (x_j - x_i)^T: column c is grad times x_ji[c].
                for (int c = 0; c < D; ++c)
                    A[c] -= x_ij[c] * grad;
                g += (state.density[j] - state.density[i]) * grad;
            }
            gradient[i] = detail::renormalisation_inverse<D>(A) * g;
        }
    }
    // Antuono et al.'s delta l c0, with l = h / 2.
    const Real diffusion = delta * (params.h / 2) * params.sound_speed();
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        const Real rho_i = state.density[i];
        Real sum = sum_over_neighbours(neighbours, i, [&](std::uint32_t j) {
            const Vec<D> x_ij = state.position[i] - state.position[j];
            const Real r2 = squared_length<D>(x_ij);
            const Real r = std::sqrt(r2);
            const Vec<D> grad = pair_gradient(kernel, state, i, j, x_ij, r);
            const Vec<D> v_ij = state.velocity[i] - state.velocity[j];
            return params.mass * glm::dot(v_ij, grad);
        });
        if (delta > 0)
            sum += diffusion * sum_over_neighbours(neighbours, i, [&](std::uint32_t j) {
                       const Vec<D> x_ij = state.position[i] - state.position[j];
                       const Real r2 = squared_length<D>(x_ij);
                       const Vec<D> grad = pair_gradient(kernel, state, i, j, x_ij, std::sqrt(r2));
                       // + 1e-4 l^2 (l = h / 2) keeps coincident particles finite.
                       const Real spread = Real(2) * (state.density[j] - rho_i) /
                                           (r2 + Real(2.5e-5) * params.h * params.h);
                       const Vec<D> psi = -spread * x_ij - (gradient[i] + gradient[j]);
                       return params.mass / state.density[j] * glm::dot(psi, grad);
                   });
        if (boundary) {
            const auto xb = boundary->positions();
            const auto volume = boundary->volumes();
            const auto wall_velocity = boundary->velocities();
            sum += params.rest_density *
                   sum_over_neighbours(boundary_neighbours, i, [&](std::uint32_t b) {
                       const Vec<D> x_ib = state.position[i] - xb[b];
                       const Real r = std::sqrt(squared_length<D>(x_ib));
                       const Vec<D> v_ib = state.velocity[i] - wall_velocity[b];
                       return volume[b] * glm::dot(v_ib, boundary_gradient(kernel, x_ib, r));
                   });
        }
        rate[i] = sum;
    }
}

} // namespace sph
