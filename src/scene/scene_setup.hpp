#pragma once
// From a scene to a ready simulation: parameters, the initial particles on
// their lattice, the effects the scene names, the solver and the search.

#include "scene/scene.hpp"
#include "sph/simulation.hpp"

namespace sph {

template <int D>
Params<D> make_params(const Scene& scene, const Derived& derived);

// The scene's paddles (effects.paddles) as the core's; the renderer draws
// them where their motion has them at a frame's time.
template <int D>
std::vector<Paddle<D>> make_paddles(const Scene& scene);

// Every block filled on its lattice, ids in creation order.
template <int D>
State<D> make_initial_state(const Scene& scene, const Derived& derived);

// Exactly the effects the scene lists, in a fixed order.
template <int D>
EffectList<D> make_effects(const Scene& scene);

// The particle sources the scene lists (effects.emitters), in its order.
template <int D>
SourceList<D> make_sources(const Scene& scene);

// `partition`: over MPI ranks, how the simulation is shared out
// (sph/partition.hpp); empty: one process.
template <int D>
Simulation<D> make_simulation(const Scene& scene, const Derived& derived,
                              const PartitionMaker<D>& partition = {});

template <int D>
Simulation<D> make_simulation(const Scene& scene) {
    return make_simulation<D>(scene, derive(scene));
}

} // namespace sph
