#pragma once
// Particle sources: what adds fluid during a run (effects.emitters). A source
// is not a force: it acts between steps, before a step is sized or saved for
// the watchdog's retries, so a retried step keeps what it added. The step
// holds a list built once from the scene: a source the scene does not name is
// not in it.

#include "sph/collective.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"

#include <cstddef>
#include <memory>
#include <string_view>
#include <vector>

namespace sph {

template <int D>
class Source {
  public:
    virtual ~Source() = default;
    // The key naming it in the scene's `effects` object, and its stage.
    virtual std::string_view name() const = 0;
    // Adds the particles due by `time`, when a step starts there. New
    // particles get the next ids, and every array of the state grows with
    // them (State::resize). Over MPI ranks (`ranks` not null) `state` holds
    // this rank's particles: what depends on all of them is asked of
    // `ranks`, and new particles go to the rank that holds the end.
    virtual void emit(const Params<D>& params, Real time, State<D>& state,
                      Collective* ranks = nullptr) = 0;
    // The speed it gives the particles it makes (m/s), known before any
    // step, for the time step's first estimate.
    virtual Real speed() const = 0;
    // Bytes of the arrays it keeps.
    virtual std::size_t bytes() const { return 0; }
};

template <int D>
using SourceList = std::vector<std::unique_ptr<Source<D>>>;

} // namespace sph
