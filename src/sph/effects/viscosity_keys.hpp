#pragma once
// The scene's `effects.viscosity`: one key for the two models of a fluid's
// own viscosity, the seed's (seed_viscosity.hpp) and Morris's
// (laminar_viscosity.hpp). mu 0 is no effect. Morris's term joins the
// single-precision passes; the seed's reads neighbour lists.

#include "sph/effects/laminar_viscosity.hpp"
#include "sph/effects/seed_viscosity.hpp"
#include "sph/scene_key.hpp"

#include <array>
#include <string>

namespace sph {

enum class ViscosityModel { seed, morris };
inline constexpr std::array<const char*, 2> viscosity_model_names{"seed", "morris"};

struct ViscositySettings {
    static constexpr const char* key = "viscosity"; // in the scene's `effects`
    ViscosityModel model = ViscosityModel::morris;  // the scene's default: the solver's
    double mu = 0;                                  // Pa.s; the scene's default: material.viscosity
    // Viscosity is a property of the fluid: without the key, material.viscosity
    // with the solver's model, on wherever mu > 0. (`Scene` is the rest of the
    // scene, read before the effects: scene/keys/effect_registry.hpp.)
    template <class Scene>
    static ViscositySettings defaults(const Scene& scene) {
        return {scene.capabilities.viscosity_model, scene.material_viscosity};
    }
    template <class Scene>
    static bool implied(const Scene&) {
        return true;
    }
    bool on() const { return mu > 0; }
    // Written 0 when off, so that read back nothing implies it.
    static constexpr const char* off_key = "mu";
    EffectCapabilities capabilities() const {
        return {.reads_neighbour_lists = model != ViscosityModel::morris};
    }
    // Either model diffuses momentum at mu: the time step's diffusion
    // condition (time_step.hpp), as the built effect's diffusion_viscosity().
    double diffusion_viscosity() const { return mu; }
    // How the scene's checks name it.
    std::string label() const {
        return std::string("effects.viscosity model ") +
               viscosity_model_names[static_cast<std::size_t>(model)];
    }
};

inline const KeyTable<ViscositySettings>& viscosity_keys() {
    static const KeyTable<ViscositySettings> keys{
        {.path = "model",
         .field = enum_field<&ViscositySettings::model>(),
         .doc = "Viscosity effect: seed (the report's term, Müller et al. 2003) or morris "
                "(Morris et al. 1997, laminar, suited to very viscous fluids, no-slip walls).",
         .choices = {"seed", "morris"},
         .absent = "seed for the seed solver, morris for the others"},
        {.path = "mu",
         .field = &ViscositySettings::mu,
         .unit = "Pa.s",
         .doc = "Viscosity effect: dynamic viscosity; default material.viscosity.",
         .bound = Bound::non_negative},
    };
    return keys;
}

template <int D>
std::unique_ptr<Effect<D>> make_effect(const ViscositySettings& s) {
    if (s.model == ViscosityModel::seed)
        return std::make_unique<SeedViscosity<D>>(s.mu);
    return std::make_unique<LaminarViscosity<D>>(s.mu);
}

} // namespace sph
