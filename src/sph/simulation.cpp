#include "sph/simulation.hpp"

namespace sph {

template <int D>
Simulation<D>::Simulation(const Params<D>& params, State<D> initial,
                          std::unique_ptr<Solver<D>> solver,
                          std::unique_ptr<NeighbourSearch<D>> search, EffectList<D> effects)
    : params_(params), state_(std::move(initial)), solver_(std::move(solver)),
      search_(std::move(search)), effects_(std::move(effects)) {}

template <int D>
void Simulation<D>::step() {
    auto ctx = context();
    solver_->step(params_, state_, ctx);
    ++steps_;
    // Fixed dt: time from the step count, so no rounding accumulates.
    time_ = Real(steps_) * params_.dt;
    check_finite(state_, steps_, time_);
}

template <int D>
void Simulation<D>::advance_to(Real t) {
    // A frame time reached up to rounding counts as reached.
    const Real tolerance = 1e-9 * params_.dt;
    while (time_ < t - tolerance)
        step();
}

template <int D>
void Simulation<D>::update_fields() {
    auto ctx = context();
    solver_->update_fields(params_, state_, ctx);
}

template class Simulation<2>;
template class Simulation<3>;

} // namespace sph
