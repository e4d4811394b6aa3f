#pragma once
// The watchdog: cheap checks after every step, so that numerical trouble is
// caught where it starts and named, never silently clamped or dropped.
//   - a non-finite value anywhere (density, pressure, acceleration, velocity,
//     position, or a speed too large to square);
//   - a particle that moved more than watchdog.max_displacement support radii
//     in one step: it crossed its neighbourhood, the CFL condition is broken;
//   - a speed above watchdog.max_speed: twice what the scene's physics can
//     give (sound speed + free fall over the box + fastest start), which no
//     step size makes right;
//   - a density above watchdog.max_density_ratio times the rest density: the
//     fluid is collapsing (no liquid is compressed several-fold).
// Simulation retries a step that fails them with the step halved (from a saved
// state); only when the retries run out does it throw UnstableError.

#include "sph/collective.hpp"
#include "sph/params.hpp"
#include "sph/state.hpp"

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>

namespace sph {

// What the watchdog found wrong after a step.
struct StepProblem {
    std::uint32_t particle = 0; // the particle's id
    std::string quantity;       // e.g. "velocity.y", "density", "displacement / h"
    Real value = 0;
    Real limit = 0; // the bound it broke; infinity for a non-finite value
};

// Over MPI ranks (`ranks` not null) `state` is this rank's particles: every
// rank gets the same answer, the problem one process would have named.
template <int D>
std::optional<StepProblem> inspect_step(const Params<D>& params, const State<D>& state, Real dt,
                                        Collective* ranks = nullptr);

// The run cannot go on: a step failed the watchdog even at its smallest retry.
struct UnstableError : std::runtime_error {
    std::uint64_t step; // the step that failed (1 = the first)
    Real time;          // s, the time that step started from
    StepProblem problem;
    int retries; // times the step was halved and retried
    Real dt;     // s, the smallest step tried
    // `cause`, when known, says what in the scene led there; it comes before
    // the advice.
    UnstableError(std::uint64_t step, Real time, StepProblem problem, int retries, Real dt,
                  const std::string& cause = {});
};

} // namespace sph
