#pragma once
// Effects are the non-pressure forces a scene asks for. The step holds a list
// built once from the scene: an effect the scene does not name is not in the
// list, allocates nothing and costs nothing per step.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"

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

// The effect of kind T in the list, or null: for a solver that computes it
// inside a pass of its own (and then tells apply_effects to skip it).
template <class T, int D>
const T* find_effect(const EffectList<D>& effects) {
    for (const auto& effect : effects)
        if (const auto* found = dynamic_cast<const T*>(effect.get()))
            return found;
    return nullptr;
}

} // namespace sph
