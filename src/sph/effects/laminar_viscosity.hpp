#pragma once
// Laminar viscosity of a Newtonian fluid with dynamic viscosity mu (Morris,
// Fox & Zhu 1997, eq. 8, Brookshaw's second derivative):
//   a_i += (2 mu / rho_i) sum_j m / rho_j (x_ij . grad W_ij) / (r^2 + 0.01 h_M^2) v_ij
// with h_M = h / 2 Morris's smoothing length (our h is the support radius):
// the term only keeps r = 0 finite, and with h^2 in its place it would bias
// every nearest-neighbour pair by about 6% (the shear-wave test sees 4%).
// It stays accurate for very viscous fluids (honey, lava), where the seed's
// term and the artificial one do not model the fluid's own viscosity. The
// walls, obstacles and paddles are no-slip: a boundary particle counts as
// fluid of density rho0, mass rho0 V_b and its own velocity v_b (0 but on a
// paddle, sph/paddles.hpp), so v_ib = v_i - v_b.
// The scene's `effects.viscosity` with model "morris" (the default of the
// wcsph and dfsph solvers).

#include "sph/effects/effect.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbours/neighbour_sum.hpp"

#include <cmath>

namespace sph {

// One pair's share of Morris's sum, before the (2 mu / rho_i) in front and
// the velocity difference after it; one division each.
struct MorrisViscosity {
    Real eps;    // 0.0025 h^2
    Real two_mu; // Pa.s

    // A fluid neighbour of mass m and density rho_j. x . grad W = r dW/dr:
    // no direction needed, fine at r = 0.
    template <class Kernel>
    Real fluid(const Kernel& kernel, Real m, Real rho_j, Real r, Real r2) const {
        const Real x_dot_grad = r * kernel.dW(r);
        return m * x_dot_grad / (rho_j * (r2 + eps));
    }
    // The same from dW/dr / r, for a pass that has it for the pressure's
    // gradient already: x . grad W = r^2 (dW/dr / r), so the kernel's
    // derivative is not evaluated twice (wcsph's 3D pressure pass 154-172 ->
    // 136-149 ns a particle-step in five interleaved runs, docs/benchmarks.md).
    Real fluid_from_factor(Real m, Real rho_j, Real r2, Real dW_over_r) const {
        return m * r2 * dW_over_r / (rho_j * (r2 + eps));
    }
    // A boundary particle of volume V_b (fluid of density rho0, mass rho0 V_b).
    template <class Kernel>
    Real wall(const Kernel& kernel, Real volume, Real r, Real r2) const {
        return volume * r * kernel.dW(r) / (r2 + eps);
    }
    // Either, in float, from the neighbour's volume (m / rho_j, or V_b) and
    // x . grad W: the single-precision passes' term (sph/single_precision/).
    struct Single {
        float eps, two_mu;
        float operator()(float volume, float x_dot_grad, float r2) const {
            return volume * x_dot_grad / (r2 + eps);
        }
    };
    Single single() const { return {float(eps), float(two_mu)}; }
};

template <int D>
class LaminarViscosity final : public Effect<D> {
  public:
    explicit LaminarViscosity(Real mu) : mu_(mu) {}
    std::string_view name() const override { return "viscosity"; }
    Real diffusion_viscosity() const override { return mu_; }
    // wcsph computes it with the pressure, over the same pairs.
    static constexpr PressurePassTerm pressure_pass = PressurePassTerm::morris_viscosity;
    PressurePassTerm pressure_pass_term() const override { return pressure_pass; }
    Real mu() const { return mu_; }
    MorrisViscosity pair_viscosity(const Params<D>& params) const {
        return {Real(0.0025) * params.h * params.h, 2 * mu_};
    }

    void apply(const Params<D>& params, const EffectInputs<D>& in, State<D>& state) override {
        with_kernel<D>(params.kernel, params.h,
                       [&](const auto& kernel) { add(params, kernel, in, state); });
    }

  private:
    template <class Kernel>
    void add(const Params<D>& params, const Kernel& kernel, const EffectInputs<D>& in,
             State<D>& state) const {
        const std::size_t n = state.size();
        const MorrisViscosity morris = pair_viscosity(params);
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> a = sum_over_neighbours(in.neighbours, i, [&](std::uint32_t j) {
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r2 = squared_length<D>(x_ij);
                const Real r = std::sqrt(r2);
                return morris.fluid(kernel, params.mass, state.density[j], r, r2) *
                       (state.velocity[i] - state.velocity[j]);
            });
            if (in.boundary) {
                const auto xb = in.boundary->positions();
                const auto volume = in.boundary->volumes();
                // A local span, not in.boundary->velocity(b): the loop then vectorises.
                const auto wall_velocity = in.boundary->velocities();
                a += sum_over_neighbours(in.boundary_neighbours, i, [&](std::uint32_t b) {
                    const Vec<D> x_ib = state.position[i] - xb[b];
                    const Real r2 = squared_length<D>(x_ib);
                    const Real r = std::sqrt(r2);
                    return morris.wall(kernel, volume[b], r, r2) *
                           (state.velocity[i] - wall_velocity[b]);
                });
            }
            state.acceleration[i] += (morris.two_mu / state.density[i]) * a;
        }
    }

    Real mu_; // Pa.s
};

} // namespace sph
