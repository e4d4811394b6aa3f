#pragma once
// Uniform gravity, the seed's body force: a_i += g.

#include "sph/effects/effect.hpp"

namespace sph {

// The scene's `effects.gravity`: the acceleration itself, not an object.
struct GravitySettings {
    static constexpr const char* key = "gravity"; // in the scene's `effects`
    Vec3 acceleration{0, -9.81, 0};               // m/s^2
    EffectCapabilities capabilities() const { return {}; }
    // How the scene's checks name it.
    std::string label() const { return "effects.gravity"; }
};

inline const KeyTable<GravitySettings>& gravity_keys() {
    static const KeyTable<GravitySettings> keys{
        {.path = "",
         .field = &GravitySettings::acceleration,
         .unit = "m/s^2",
         .doc = "Gravity effect: a uniform acceleration. Absent from an `effects` object the "
                "scene gives (or null): no gravity.",
         .nullable = true},
    };
    return keys;
}

template <int D>
class Gravity final : public Effect<D> {
  public:
    explicit Gravity(const Vec<D>& g) : g_(g) {}
    std::string_view name() const override { return "gravity"; }
    void apply(const Params<D>&, const EffectInputs<D>&, State<D>& state) override {
        const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i)
            state.acceleration[i] += g_;
    }
    const Vec<D>& acceleration() const {
        return g_;
    }
    Real body_acceleration() const override {
        return glm::length(g_);
    }

  private:
    Vec<D> g_;
};

template <int D>
std::unique_ptr<Effect<D>> make_effect(const GravitySettings& s) {
    Vec<D> g;
    for (int a = 0; a < D; ++a)
        g[a] = s.acceleration[a];
    return std::make_unique<Gravity<D>>(g);
}

} // namespace sph
