#include "sph/solvers/seed.hpp"

#include "sph/density.hpp"
#include "sph/effects/seed_viscosity.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/kernels.hpp"
#include "sph/pair_direction.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace sph {

template <int D>
SeedSolver<D>::SeedSolver(KernelKind kernel) : kernel_(kernel) {}

template <int D>
void SeedSolver<D>::compute_accelerations(const Params<D>& params, State<D>& state,
                                          StepContext<D>& context) {
    const auto* viscosity = fused_effect<SeedViscosity<D>>(context.effects);
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        // 1. Neighbours closer than h (the seed's spatial hash by default).
        context.find_neighbours(state.position, params.h);
        // 2. Density by summation (the seed's poly6); p = K (rho - rho0) / rho0.
        {
            auto timed = context.time(Stage::density);
            compute_density(params, kernel, context.neighbours, state);
            compute_pressure_linear(params, state);
        }
        // Over ranks: the halo's densities and pressures from their owners.
        context.share_halo_densities(state);
        // 3. The seed's pair force f_ij, a = f / rho: its pressure half, and
        // its viscous half (effects/seed_viscosity.hpp) when the scene has
        // it, in the same pass over the pairs (timed as "pressure").
        auto timed = context.time(Stage::pressure);
        compute_seed_pressure(params, kernel, context.neighbours, viscosity, state);
    });
    // 4. Gravity and the other effects the scene names.
    const std::array<const Effect<D>*, 1> merged{viscosity};
    context.apply_effects(params, state, merged);
}

template <int D>
void SeedSolver<D>::update_fields(const Params<D>& params, State<D>& state,
                                  StepContext<D>& context) {
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        context.find_neighbours(state.position, params.h);
        compute_density(params, kernel, context.neighbours, state);
        if (context.output_pressure) // the next step computes its own
            compute_pressure_linear(params, state);
    });
}

// The seed's interaction force (MODEL.md), written with the kernels it comes
// from (Müller et al. 2003, eqs. 10, 14, 21, 22):
//   f_ij = m / rho_j [ -(p_i + p_j) / 2  grad W_spiky(r_ij)  -  mu v_ij lap W_visc(r) ]
// with p = K (rho - rho0) / rho0 (equation_of_state.hpp), r_ij = r_i - r_j,
// v_ij = v_i - v_j, q = r / h. In 2D (W_spiky = 10/(pi h^5) (h-r)^3,
// lap W_visc = 40/(pi h^5) (h-r)) this is the seed's expression term by term:
//   m/(pi h^4 rho_j) (1-q) [15 K' (rho_i + rho_j - 2 rho0) (1-q)/q r_ij - 40 mu v_ij]
// with the seed's K' = K / rho0. In 3D (15/(pi h^6) (h-r)^3 and
// 45/(pi h^6) (h-r)) it becomes
//   m/(pi h^5 rho_j) (1-q) [45/2 K' (rho_i + rho_j - 2 rho0) (1-q)/q r_ij - 45 mu v_ij].
// The seed's 1/q only stands for the direction r_ij / r; at r = 0 the
// magnitude is finite and coincident_direction() supplies the direction.
// The pressure half is the solver's; the viscous half is the `viscosity`
// effect with model "seed" (effects/seed_viscosity.hpp), so a scene without
// viscosity does not pay for it. With it, the solver adds both halves in one
// pass over the pairs, sharing r and the densities.
//
// The acceleration it gives i, f_ij / rho_i = m / (rho_i rho_j) [...], is
// symmetric in i and j but for the sign of r_ij and v_ij: this is why the seed
// can compute it once per pair and apply it with opposite signs. Evaluated
// here as one expression whose every operation commutes, the two sides are
// exact negatives of each other.
namespace {

// The pressure term with its kernel built once per stage, not once per pair.
// Another kernel than the seed's replaces spiky's gradient by its own.
template <int D, class Kernel>
struct SeedPressureTerm {
    const Params<D>& params;
    const Kernel& kernel;

    Vec<D> operator()(const State<D>& state, std::size_t i, std::size_t j) const {
        const Vec<D> r_ij = state.position[i] - state.position[j];
        const Real r = std::sqrt(squared_length<D>(r_ij));
        return (*this)(state, i, j, r_ij, r);
    }
    Vec<D> operator()(const State<D>& state, std::size_t i, std::size_t j, const Vec<D>& r_ij,
                      Real r) const {
        const Vec<D> direction = pair_direction(state, i, j, r_ij, r, params.h);
        const Real mean_pressure = Real(0.5) * (state.pressure[i] + state.pressure[j]);
        return (-params.mass * mean_pressure * kernel.dW(r) /
                (state.density[i] * state.density[j])) *
               direction;
    }
};

} // namespace

template <int D>
Vec<D> seed_pair_acceleration(const Params<D>& params, Real mu, const State<D>& state,
                              std::size_t i, std::size_t j) {
    const SeedKernel<D> kernel(params.h);
    return SeedPressureTerm<D, SeedKernel<D>>{params, kernel}(state, i, j) +
           seed_viscous_acceleration(params, ViscosityLaplacian<D>(params.h), mu, state, i, j);
}

template <int D>
Vec<D> seed_pair_force(const Params<D>& params, Real mu, const State<D>& state, std::size_t i,
                       std::size_t j) {
    return state.density[i] * seed_pair_acceleration(params, mu, state, i, j);
}

// Gather-style: each particle sums its own side of every pair, so threads
// never write to the same particle and the sum is the same for any thread
// count; the seed's once-per-pair evaluation gives the same values.
template <int D, class Kernel>
void compute_seed_pressure(const Params<D>& params, const Kernel& kernel,
                           const NeighbourList& neighbours, const SeedViscosity<D>* viscosity,
                           State<D>& state) {
    const std::size_t n = state.size();
    const SeedPressureTerm<D, Kernel> term{params, kernel};
    const ViscosityLaplacian<D> laplacian(params.h);
    const Real mu = viscosity ? viscosity->mu() : 0;
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D> acceleration(0);
        for (std::uint32_t j : neighbours.of(i)) {
            const Vec<D> r_ij = state.position[i] - state.position[j];
            const Real r = std::sqrt(squared_length<D>(r_ij));
            acceleration += term(state, i, j, r_ij, r);
            if (viscosity)
                acceleration += seed_viscous_acceleration(params, laplacian, mu, state, i, j, r);
        }
        state.acceleration[i] = acceleration;
    }
}

template class SeedSolver<2>;
template class SeedSolver<3>;
template <int D>
void compute_seed_interaction(const Params<D>& params, Real mu, const NeighbourList& neighbours,
                              State<D>& state) {
    const SeedViscosity<D> viscosity(mu);
    compute_seed_pressure(params, SeedKernel<D>(params.h), neighbours, &viscosity, state);
}

template void compute_seed_interaction<2>(const Params<2>&, Real, const NeighbourList&, State<2>&);
template void compute_seed_interaction<3>(const Params<3>&, Real, const NeighbourList&, State<3>&);
template Vec<2> seed_pair_force<2>(const Params<2>&, Real, const State<2>&, std::size_t,
                                   std::size_t);
template Vec<3> seed_pair_force<3>(const Params<3>&, Real, const State<3>&, std::size_t,
                                   std::size_t);
template Vec<2> seed_pair_acceleration<2>(const Params<2>&, Real, const State<2>&, std::size_t,
                                          std::size_t);
template Vec<3> seed_pair_acceleration<3>(const Params<3>&, Real, const State<3>&, std::size_t,
                                          std::size_t);

} // namespace sph
