#pragma once
// XSPH velocity smoothing (Monaghan 1989, "On the problem of penetration in
// particle methods", eq. 2.6): each particle's velocity is drawn toward the
// kernel-weighted mean of its neighbours',
//   v_i <- v_i + epsilon sum_j m / rho_ij (v_j - v_i) W_ij,  rho_ij = (rho_i + rho_j) / 2
// which keeps particle streams from interpenetrating and calms the noise of
// a weakly compressible fluid without the artificial term's damping of
// compression. Written as the acceleration that makes this change over the
// step, (epsilon / dt) sum_j ..., as SPlisHSPlasH's XSPH viscosity does, so
// it joins the other forces; the weights are symmetric, so momentum is
// conserved. epsilon in (0, 1]: 1 replaces v_i by the local mean velocity.
// The scene's `effects.xsph`.

#include "sph/effects/effect.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbours/neighbour_sum.hpp"

#include <cmath>
#include <fmt/format.h>
#include <optional>

namespace sph {

// The scene's `effects.xsph`.
struct XsphSettings {
    static constexpr const char* key = "xsph"; // in the scene's `effects`
    double epsilon = 0.5; // fraction of the way to the neighbours' mean velocity, in (0, 1]
    EffectCapabilities capabilities() const { return {.reads_neighbour_lists = true}; }
    // Above 1 it would overshoot the mean.
    std::optional<KeyProblem> problem() const {
        if (!(epsilon > 1))
            return std::nullopt;
        return KeyProblem{"epsilon",
                          fmt::format("{} is above 1: XSPH would overshoot the neighbours' mean "
                                      "velocity",
                                      epsilon)};
    }
    // How the scene's checks name it.
    std::string label() const { return "effects.xsph"; }
};

inline const KeyTable<XsphSettings>& xsph_keys() {
    static const KeyTable<XsphSettings> keys{
        {.path = "epsilon",
         .field = &XsphSettings::epsilon,
         .doc = "XSPH velocity smoothing effect (Monaghan 1989): each step draws a particle's "
                "velocity this fraction of the way to its neighbours' mean; in (0, 1]. Absent: "
                "none.",
         .bound = Bound::positive},
    };
    return keys;
}

template <int D>
class Xsph final : public Effect<D> {
  public:
    explicit Xsph(Real epsilon) : epsilon_(epsilon) {}
    std::string_view name() const override { return "xsph"; }
    Real epsilon() const { return epsilon_; }

    void apply(const Params<D>& params, const EffectInputs<D>& in, State<D>& state) override {
        if (!(in.dt > 0))
            return; // no step to smooth over
        with_kernel<D>(params.kernel, params.h, [&](const auto& kernel) {
            const std::size_t n = state.size();
            const Real scale = 2 * epsilon_ * params.mass / in.dt;
#pragma omp parallel for schedule(dynamic, 256)
            for (std::size_t i = 0; i < n; ++i) {
                const Vec<D> a = sum_over_neighbours(in.neighbours, i, [&](std::uint32_t j) {
                    const Real r =
                        std::sqrt(squared_length<D>(state.position[i] - state.position[j]));
                    return (kernel.W(r) / (state.density[i] + state.density[j])) *
                           (state.velocity[j] - state.velocity[i]);
                });
                state.acceleration[i] += scale * a;
            }
        });
    }

  private:
    Real epsilon_;
};

template <int D>
std::unique_ptr<Effect<D>> make_effect(const XsphSettings& s) {
    return std::make_unique<Xsph<D>>(s.epsilon);
}

} // namespace sph
