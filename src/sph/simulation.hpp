#pragma once
// One simulation: fixed parameters, the particle state, and the parts a step is
// built from (solver, neighbour search, effects), all chosen once from the
// scene. Simulation time advances in steps of params.dt, independent of the
// frame rate; callers take frames whenever time crosses k / fps.

#include "sph/checks.hpp"
#include "sph/solvers/solver.hpp"

#include <cstdint>
#include <memory>

namespace sph {

template <int D>
class Simulation {
  public:
    Simulation(const Params<D>& params, State<D> initial, std::unique_ptr<Solver<D>> solver,
               std::unique_ptr<NeighbourSearch<D>> search, EffectList<D> effects);

    // One time step, then the finite check (throws NonFiniteError).
    void step();
    // Steps until time() >= t (up to rounding of the accumulated time).
    void advance_to(Real t);
    // Density and pressure at the current positions, for output.
    void update_fields();

    const Params<D>& params() const { return params_; }
    const State<D>& state() const { return state_; }
    State<D>& state() { return state_; }
    const Solver<D>& solver() const { return *solver_; }
    const NeighbourSearch<D>& search() const { return *search_; }
    // Neighbours as the last step or update_fields() found them.
    const NeighbourList& neighbours() const { return neighbours_; }
    const EffectList<D>& effects() const { return effects_; }
    Real time() const { return time_; }
    std::uint64_t steps() const { return steps_; }

  private:
    StepContext<D> context() { return {*search_, neighbours_, effects_}; }

    Params<D> params_;
    State<D> state_;
    std::unique_ptr<Solver<D>> solver_;
    std::unique_ptr<NeighbourSearch<D>> search_;
    EffectList<D> effects_;
    NeighbourList neighbours_;
    Real time_ = 0;
    std::uint64_t steps_ = 0;
};

} // namespace sph
