#pragma once
// The effects a scene can name, one line each, in the order the step applies
// them (the order is part of the arithmetic: frames depend on it). Each
// effect's settings, keys, capabilities and factory (make_effect) live in its
// file under sph/effects/; reading, run.json, the single-precision check
// and make_effects walk this list. docs/adding-an-effect.md has the recipe.

#include "io/scene.hpp"

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

} // namespace sph
