#pragma once
// Density by kernel summation over the neighbours, the particle itself included
// (Müller et al. 2003, eq. 3; the seed's density):  rho_i = sum_j m W(|r_i - r_j|).

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"
#include "sph/vector_clones.hpp"

#include <cmath>

namespace sph {

// A kernel that offers W from the squared distance skips a square root.
template <class Kernel>
Real kernel_value_squared(const Kernel& kernel, Real r2) {
    if constexpr (requires { kernel.W_r2(r2); })
        return kernel.W_r2(r2);
    else
        return kernel.W(std::sqrt(r2));
}

template <int D, class Kernel>
SPHCLIP_CLONED void compute_density(const Params<D>& params, const Kernel& kernel,
                                    const NeighbourList& neighbours, State<D>& state) {
    const std::size_t n = state.size();
    const Real self = kernel_value_squared(kernel, Real(0));
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        const Real sum = sum_over_neighbours(neighbours, i, [&](std::uint32_t j) {
            return kernel_value_squared(kernel,
                                        squared_length<D>(state.position[i] - state.position[j]));
        });
        state.density[i] = params.mass * (self + sum);
    }
}

// The walls' share of the density: rho_i += sum_b rho0 V_b W_ib
// (Akinci et al. 2012, eq. 6).
template <int D, class Kernel>
SPHCLIP_CLONED void add_boundary_density(const Params<D>& params, const Kernel& kernel,
                                         const BoundaryParticles<D>& boundary,
                                         const NeighbourList& boundary_neighbours,
                                         State<D>& state) {
    const std::size_t n = state.size();
    const auto xb = boundary.positions();
    const auto volume = boundary.volumes();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        const Real sum = sum_over_neighbours(boundary_neighbours, i, [&](std::uint32_t b) {
            return volume[b] *
                   kernel_value_squared(kernel, squared_length<D>(state.position[i] - xb[b]));
        });
        state.density[i] += params.rest_density * sum;
    }
}

} // namespace sph
