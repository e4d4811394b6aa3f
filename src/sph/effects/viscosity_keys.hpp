#pragma once
// The scene's `effects.viscosity`: one key for the two models of a fluid's
// own viscosity, the seed's (seed_viscosity.hpp) and Morris's
// (laminar_viscosity.hpp). mu 0 is no effect.

#include "sph/scene_key.hpp"

#include <string>

namespace sph {

struct ViscositySettings {
    std::string model; // seed | morris; the scene's default: the solver's
    double mu = 0;     // Pa.s; the scene's default: material.viscosity
};

inline const KeyTable<ViscositySettings>& viscosity_keys() {
    static const KeyTable<ViscositySettings> keys{
        {.path = "model",
         .field = &ViscositySettings::model,
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

} // namespace sph
