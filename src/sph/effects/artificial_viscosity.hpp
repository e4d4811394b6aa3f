#pragma once
// Monaghan's artificial viscosity (Monaghan 1992, eq. 4.1, without the
// quadratic beta term), acting only between approaching particles:
//   Pi_ij = -(2 alpha h c / (rho_i + rho_j)) (v_ij . x_ij) / (r^2 + 0.01 h^2)  if v_ij . x_ij < 0
//   a_i -= sum_j m Pi_ij grad W_ij
// with h the support radius and c the sound speed. It damps the noise a
// weakly compressible fluid rings with, at the price of some extra
// dissipation. The scene's `effects.artificial_viscosity` (and the older
// `solver.artificial_viscosity`, on by default for wcsph and dfsph).

#include "sph/effects/effect.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/pair_direction.hpp"

#include <cmath>
#include <concepts>

namespace sph {

// The scene's `effects.artificial_viscosity`; alpha 0 is no effect.
struct ArtificialViscositySettings {
    static constexpr const char* key = "artificial_viscosity"; // in the scene's `effects`
    // The scene's default: solver.artificial_viscosity.
    double alpha = 0;
    // Without the key, solver.artificial_viscosity, on for a solver that
    // declares it its default (wcsph, dfsph) where alpha > 0.
    template <class Scene>
    static ArtificialViscositySettings defaults(const Scene& scene) {
        return {scene.solver.artificial_viscosity};
    }
    template <class Scene>
    static bool implied(const Scene& scene) {
        return scene.capabilities.default_artificial_viscosity;
    }
    bool on() const { return alpha > 0; }
    // Written 0 when off, so that read back nothing implies it.
    static constexpr const char* off_key = "alpha";
    EffectCapabilities capabilities() const { return {}; }
    // How the scene's checks name it.
    std::string label() const { return "effects.artificial_viscosity"; }
};

inline const KeyTable<ArtificialViscositySettings>& artificial_viscosity_keys() {
    static const KeyTable<ArtificialViscositySettings> keys{
        {.path = "alpha",
         .field = &ArtificialViscositySettings::alpha,
         .doc = "Artificial viscosity effect (Monaghan 1992), its alpha; default "
                "solver.artificial_viscosity. Without the key, wcsph and dfsph use "
                "solver.artificial_viscosity and the seed none.",
         .bound = Bound::non_negative},
    };
    return keys;
}

// Pi_ij of one pair, from v_ij . x_ij, rho_i + rho_j and r^2. Receding pairs
// (v . x >= 0) give 0: a select, not a branch, and one division (the rest of
// Pi grad W is products). At r = 0, v . x is 0 too.
template <std::floating_point T>
struct MonaghanTerm {
    T nu_scale; // 2 alpha h c
    T eps;      // 0.01 h^2

    T operator()(T rate, T density_sum, T r2) const {
        const T v_dot_x = rate < 0 ? rate : 0; // not std::min: its reference
                                               // keeps the loop scalar
        return -nu_scale * v_dot_x / (density_sum * (r2 + eps));
    }
    // The same for each lane of a register (GCC's vector extension), into
    // `Pi`: a wide vector returned by value changes the ABI without AVX.
    template <class Lanes>
    requires(!std::floating_point<Lanes>) void
    operator()(const Lanes& rate, const Lanes& density_sum, const Lanes& r2, Lanes& Pi) const {
        const Lanes v_dot_x = rate < 0 ? rate : Lanes{};
        Pi = -nu_scale * v_dot_x / (density_sum * (r2 + eps));
    }
    // The float term of the single-precision passes (sph/single_precision/).
    MonaghanTerm<float> single() const { return {float(nu_scale), float(eps)}; }
};
using MonaghanViscosity = MonaghanTerm<Real>;

template <int D>
class ArtificialViscosity final : public Effect<D> {
  public:
    explicit ArtificialViscosity(Real alpha) : alpha_(alpha) {}
    std::string_view name() const override { return "artificial_viscosity"; }
    // wcsph computes it with the pressure, over the same pairs.
    static constexpr PressurePassTerm pressure_pass = PressurePassTerm::monaghan_viscosity;
    PressurePassTerm pressure_pass_term() const override { return pressure_pass; }
    Real alpha() const { return alpha_; }
    MonaghanViscosity pair_viscosity(const Params<D>& params) const {
        return {2 * alpha_ * params.h * params.sound_speed(), Real(0.01) * params.h * params.h};
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
        const MonaghanViscosity Pi = pair_viscosity(params);
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> a = -sum_over_neighbours(in.neighbours, i, [&](std::uint32_t j) {
                const Vec<D> x_ij = state.position[i] - state.position[j];
                const Real r2 = squared_length<D>(x_ij);
                const Real r = std::sqrt(r2);
                const Real Pi_ij = Pi(glm::dot(state.velocity[i] - state.velocity[j], x_ij),
                                      state.density[i] + state.density[j], r2);
                return (params.mass * Pi_ij * gradient_factor(kernel, r)) * x_ij;
            });
            // The walls too (as Akinci et al. 2012 do): a wall particle is
            // fluid with the particle's density, mass rho0 V_b and its own
            // velocity (0 but on a paddle, sph/paddles.hpp).
            // Without it a particle that comes close to a wall, where the
            // smooth kernels' gradients fade, meets no damping and squirts
            // along it.
            if (in.boundary) {
                const auto xb = in.boundary->positions();
                const auto volume = in.boundary->volumes();
                // A local span, not in.boundary->velocity(b): the loop then vectorises.
                const auto wall_velocity = in.boundary->velocities();
                a -= sum_over_neighbours(in.boundary_neighbours, i, [&](std::uint32_t b) {
                    const Vec<D> x_ib = state.position[i] - xb[b];
                    const Real r2 = squared_length<D>(x_ib);
                    const Real r = std::sqrt(r2);
                    const Real Pi_ib = Pi(glm::dot(state.velocity[i] - wall_velocity[b], x_ib),
                                          2 * state.density[i], r2);
                    return (params.rest_density * volume[b] * Pi_ib * gradient_factor(kernel, r)) *
                           x_ib;
                });
            }
            state.acceleration[i] += a;
        }
    }

    Real alpha_;
};

template <int D>
std::unique_ptr<Effect<D>> make_effect(const ArtificialViscositySettings& s) {
    return std::make_unique<ArtificialViscosity<D>>(s.alpha);
}

} // namespace sph
