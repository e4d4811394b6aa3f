#pragma once
// The end-of-run table of where the time went (run.json "stages" and the
// terminal): each stage that ran, its total seconds, its share of the run's
// wall time and its cost per particle-step.

#include "sph/stage_times.hpp"

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
};

// The simulation's stages, then `after` (render, encode, ...: stages outside
// the step), leaving out stages that took no time at all.
std::vector<StageRow> stage_rows(const StageTimes& simulation, const StageTimes& after,
                                 double wall_seconds, std::uint64_t particle_steps);

nlohmann::json stages_json(const std::vector<StageRow>& rows);
// Aligned text table, one stage a line, with a header.
std::string stages_table(const std::vector<StageRow>& rows);

} // namespace sph
