#pragma once
// The interface every solver implements. A solver's step() reads like its
// algorithm: a named call per stage, the stages themselves in their own files.

#include "sph/effects/effect.hpp"
#include "sph/neighbours/neighbour_search.hpp"

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// What a step needs besides parameters and state: the neighbour search and the
// lists it fills (reused every step), and the scene's effects.
template <int D>
struct StepContext {
    NeighbourSearch<D>& search;
    NeighbourList& neighbours;
    const EffectList<D>& effects;
};

template <int D>
class Solver {
  public:
    virtual ~Solver() = default;
    virtual std::string_view name() const = 0;
    // Advances the state by params.dt.
    virtual void step(const Params<D>& params, State<D>& state, StepContext<D>& context) = 0;
    // Density and pressure at the current positions, as the next step would
    // compute them; used for the frame outputs. Moves nothing.
    virtual void update_fields(const Params<D>& params, State<D>& state,
                               StepContext<D>& context) = 0;
};

// Names accepted by make_solver (`solver.name`), in the order the README lists them.
std::vector<std::string> solver_names();

template <int D>
std::unique_ptr<Solver<D>> make_solver(std::string_view name);

} // namespace sph
