#pragma once
// Effects are the non-pressure forces a scene asks for. The step holds a list
// built once from the scene: an effect the scene does not name is not in the
// list, allocates nothing and costs nothing per step.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/params.hpp"
#include "sph/scene_key.hpp"
#include "sph/state.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

namespace sph {

// What an effect reads besides the particles: the neighbour lists the
// solver built for this step, the wall, obstacle and paddle particles (null
// when the walls reflect and there are no obstacles or paddles), and the
// step's length.
// What an effect needs of the step, declared in its settings (its file),
// so that the scene's checks ask the effect rather than know it by name.
struct EffectCapabilities {
    // Reads the neighbour lists, which wcsph's single-precision passes do not build.
    bool reads_neighbour_lists = false;
};

// A term a solver can compute inside its own pressure pass, over the same
// pairs, instead of in a pass of the effect's: the effect declares which
// (Effect::pressure_pass_term), the solver asks for the ones it fuses.
enum class PressurePassTerm {
    none,
    monaghan_viscosity, // wcsph (pressure_acceleration.hpp)
    morris_viscosity,   // wcsph, double and single precision
    seed_viscosity      // the seed solver's pair force
};

template <int D>
struct EffectInputs {
    const NeighbourList& neighbours;
    const BoundaryParticles<D>* boundary;
    const NeighbourList& boundary_neighbours; // fluid -> boundary particles
    Real dt;                                  // s
};

template <int D>
class Effect {
  public:
    virtual ~Effect() = default;
    // The key naming the effect in the scene's `effects` object.
    virtual std::string_view name() const = 0;
    // Adds this effect's acceleration to state.acceleration.
    // Not const: an effect may keep per-particle arrays of its own.
    virtual void apply(const Params<D>& params, const EffectInputs<D>& in, State<D>& state) = 0;
    // The magnitude of a uniform acceleration it gives every particle (0 if
    // none), known before any step: the time step's force condition needs
    // it on the first step, before any acceleration has been computed.
    virtual Real body_acceleration() const { return 0; }
    // The dynamic viscosity mu (Pa.s) by which it limits the time step, as
    // diffusion does (time_step.hpp); 0: no such limit.
    virtual Real diffusion_viscosity() const { return 0; }
    // The term a solver may compute for it inside its pressure pass (then
    // telling apply_effects to skip it); none: it runs on its own.
    virtual PressurePassTerm pressure_pass_term() const { return PressurePassTerm::none; }
    // Bytes of the arrays it keeps (its own per-particle arrays); an
    // effect the scene does not name is not built and holds none.
    virtual std::size_t bytes() const { return 0; }
    // The particle arrays were reordered between steps (State::permute with
    // `order`): per-particle arrays kept from one step to the next must
    // follow. Nothing to do for an effect that keeps none, or that
    // recomputes its arrays every step (surface tension's normals).
    virtual void permute(std::span<const std::uint32_t> /*order*/) {}
};

template <int D>
using EffectList = std::vector<std::unique_ptr<Effect<D>>>;

// The effect that declares T's pressure-pass term (T::pressure_pass), or
// null: for a solver that computes it inside a pass of its own.
template <class T, int D>
const T* fused_effect(const EffectList<D>& effects) {
    for (const auto& effect : effects)
        if (effect->pressure_pass_term() == T::pressure_pass)
            return static_cast<const T*>(effect.get());
    return nullptr;
}

// The largest viscosity by which an effect limits the time step; 0: none.
template <int D>
Real diffusion_viscosity(const EffectList<D>& effects) {
    Real mu = 0;
    for (const auto& effect : effects)
        mu = std::max(mu, effect->diffusion_viscosity());
    return mu;
}

} // namespace sph
