#pragma once
// The effects a scene can name, one line each, in the order the step applies
// them (the order is part of the arithmetic: frames depend on it). Each
// effect's settings, keys, capabilities and factory (make_effect) live in its
// file under sph/effects/; reading, run.json, the single-precision check
// and make_effects walk this list. docs/adding-an-effect.md has the recipe.

#include "scene/scene.hpp"
#include "sph/solvers/solver.hpp"

#include <algorithm>
#include <tuple>

namespace sph {

template <class S>
struct RegisteredEffect {
    using Settings = S;
    std::optional<S> Scene::Effects::*field;
    const KeyTable<S>& (*keys)();
};

inline constexpr std::tuple registered_effects{
    RegisteredEffect<GravitySettings>{&Scene::Effects::gravity, gravity_keys},
    RegisteredEffect<ViscositySettings>{&Scene::Effects::viscosity, viscosity_keys},
    RegisteredEffect<ArtificialViscositySettings>{&Scene::Effects::artificial_viscosity,
                                                  artificial_viscosity_keys},
    RegisteredEffect<XsphSettings>{&Scene::Effects::xsph, xsph_keys},
    RegisteredEffect<SurfaceTensionSettings>{&Scene::Effects::surface_tension,
                                             surface_tension_keys},
};

// The rest of the scene, read before the effects, that an effect's defaults
// may follow (Settings::defaults and Settings::implied).
struct EffectScene {
    const SolverSettings& solver;
    const SolverCapabilities& capabilities; // the solver's
    double material_viscosity;              // Pa.s
};

// What an effect's settings may declare, and what holds where they do not:
// defaults(scene), the values of the keys a scene leaves out (S{});
// implied(scene), on without its key (never); on(), on with these values
// (always); problem(), the values against each other (none).
template <class S>
S effect_defaults(const EffectScene& scene) {
    if constexpr (requires { S::defaults(scene); })
        return S::defaults(scene);
    else
        return S{};
}
template <class S>
bool effect_implied(const EffectScene& scene) {
    if constexpr (requires { S::implied(scene); })
        return S::implied(scene);
    else
        return false;
}
template <class S>
bool effect_on(const S& settings) {
    if constexpr (requires { settings.on(); })
        return settings.on();
    else
        return true;
}
template <class S>
std::optional<KeyProblem> effect_problem(const S& settings) {
    if constexpr (requires { settings.problem(); })
        return settings.problem();
    else
        return std::nullopt;
}

// The dynamic viscosity (Pa.s) by which an effect limits the time step, as
// its settings declare (diffusion_viscosity()); 0 where they declare none.
template <class S>
double effect_diffusion_viscosity(const S& settings) {
    if constexpr (requires { settings.diffusion_viscosity(); })
        return settings.diffusion_viscosity();
    else
        return 0;
}

// Calls f(entry) for every registered effect, in order.
template <class F>
void for_each_registered_effect(F&& f) {
    std::apply([&](const auto&... entry) { (f(entry), ...); }, registered_effects);
}

// Calls f(settings) for every effect the scene has, in order.
template <class F>
void for_each_effect(const Scene::Effects& effects, F&& f) {
    for_each_registered_effect([&](const auto& entry) {
        if (const auto& settings = effects.*entry.field)
            f(*settings);
    });
}

// The largest viscosity by which the scene's effects limit the time step;
// 0: none (the scene-side twin of diffusion_viscosity(EffectList)).
inline double diffusion_viscosity(const Scene::Effects& effects) {
    double mu = 0;
    for_each_effect(effects, [&](const auto& settings) {
        mu = std::max(mu, effect_diffusion_viscosity(settings));
    });
    return mu;
}

} // namespace sph
