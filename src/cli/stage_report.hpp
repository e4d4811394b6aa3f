#pragma once
// The end-of-run table of where the time went (run.json "stages" and the
// terminal): each stage that ran, its total seconds, its share of the run's
// wall time and its cost per particle-step.

#include "sph/stage_times.hpp"
#include "sph/step_counters.hpp"

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sph {

struct StageRow {
    std::string name;
    double seconds = 0;
    double share = 0;                // of the run's wall time
    double ns_per_particle_step = 0; // seconds / particle-steps
    // Ran on a worker thread alongside the other stages (the MP4 encoder):
    // its share is not part of theirs, and all shares may add up to over 1.
    bool overlapped = false;
    // A part of the scene computed inside this stage (a viscosity in wcsph's
    // pressure pass): its time is that stage's, its own seconds are 0.
    std::string within;
    // An iterative solve's (dfsph): its cost per particle-iteration, and
    // the iterations a step took on average; 0 for the other stages.
    double ns_per_particle_iteration = 0;
    double iterations_per_step = 0;
};

// The simulation's stages, then `after` (render, readback, ...: stages
// outside the step), then `overlapped` (worker threads' busy time), leaving
// out stages that took no time at all (but the parts computed within
// another stage). `solves` and `steps` give the iterative solves' rows
// their cost per iteration.
std::vector<StageRow> stage_rows(const StageTimes& simulation, const StageTimes& after,
                                 double wall_seconds, std::uint64_t particle_steps,
                                 const StageTimes& overlapped = {}, const SolveWork& solves = {},
                                 std::uint64_t steps = 0);

nlohmann::json stages_json(const std::vector<StageRow>& rows);
// Aligned text table, one stage a line, with a header.
std::string stages_table(const std::vector<StageRow>& rows);

} // namespace sph
