#pragma once
// The seed's viscosity (MODEL.md; Müller et al. 2003, eqs. 14 and 22): the
// viscous half of the seed's pair force,
//   f_ij = -(m / rho_j) mu (v_i - v_j) lap W_visc(r),   a_i = (1 / rho_i) sum_j f_ij
// with lap W_visc = 40 / (pi h^5) (h - r) in 2D, 45 / (pi h^6) (h - r) in 3D.
// Its weight m / (rho_i rho_j) lap W is symmetric in i and j, so the pair
// accelerations are equal and opposite and momentum is conserved. Walls
// take no part: the seed's walls reflect. The scene's `effects.viscosity`
// with model "seed" (the seed solver's default); the seed solver adds it to
// its pressure force in the same pass over the pairs, which is the report's
// model term by term (solvers/seed.cpp).

#include "sph/effects/effect.hpp"
#include "sph/kernels.hpp"

#include <cmath>

namespace sph {

// The acceleration particle j, at distance r, gives particle i.
template <int D>
Vec<D> seed_viscous_acceleration(const Params<D>& params, const ViscosityLaplacian<D>& laplacian,
                                 Real mu, const State<D>& state, std::size_t i, std::size_t j,
                                 Real r) {
    return (-params.mass * mu * laplacian.laplacian(r) / (state.density[i] * state.density[j])) *
           (state.velocity[i] - state.velocity[j]);
}

template <int D>
Vec<D> seed_viscous_acceleration(const Params<D>& params, const ViscosityLaplacian<D>& laplacian,
                                 Real mu, const State<D>& state, std::size_t i, std::size_t j) {
    const Real r = std::sqrt(squared_length<D>(state.position[i] - state.position[j]));
    return seed_viscous_acceleration(params, laplacian, mu, state, i, j, r);
}

template <int D>
class SeedViscosity final : public Effect<D> {
  public:
    explicit SeedViscosity(Real mu) : mu_(mu) {}
    std::string_view name() const override { return "viscosity"; }
    Real diffusion_viscosity() const override { return mu_; }
    // The seed solver computes it inside its pair force.
    static constexpr PressurePassTerm pressure_pass = PressurePassTerm::seed_viscosity;
    PressurePassTerm pressure_pass_term() const override { return pressure_pass; }
    Real mu() const { return mu_; }

    void apply(const Params<D>& params, const EffectInputs<D>& in, State<D>& state) override {
        const ViscosityLaplacian<D> laplacian(params.h);
        const std::size_t n = state.size();
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> a(0);
            for (std::uint32_t j : in.neighbours.of(i))
                a += seed_viscous_acceleration(params, laplacian, mu_, state, i, j);
            state.acceleration[i] += a;
        }
    }

  private:
    Real mu_; // Pa.s
};

} // namespace sph
