#pragma once
// What the steps between two frames did, for stats.csv.

#include "sph/vec.hpp"

#include <cstdint>
#include <limits>

namespace sph {

struct StepCounters {
    std::uint64_t steps = 0;
    Real dt_min = std::numeric_limits<Real>::infinity(); // s
    Real dt_max = 0;                                     // s
    Real dt_sum = 0;                                     // s
    std::uint64_t pressure_iterations = 0;               // summed over the steps
    std::uint64_t divergence_iterations = 0;             // summed over the steps
    std::uint64_t retries = 0;         // steps the watchdog rejected and retried halved
    std::uint64_t obstacle_pushes = 0; // particles put back out of an obstacle, summed

    Real dt_mean() const { return steps ? dt_sum / Real(steps) : 0; }
};

// Particle-iterations of the iterative solves over a run (an iteration of a
// solve over n particles counts n): what the stage table divides their
// time by, so that a solve's cost per iteration shows apart from how many
// iterations the scene needs.
struct SolveWork {
    std::uint64_t pressure = 0;                                       // dfsph's density solve
    std::uint64_t divergence = 0;                                     // dfsph's divergence solve
    std::uint64_t pressure_iterations = 0, divergence_iterations = 0; // iterations alone
};

} // namespace sph
