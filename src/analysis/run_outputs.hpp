#pragma once
// What a finished `sphclip run` left in its folder (docs/outputs.md), read
// back for validation and studies: run.json and stats.csv, by key and column
// name.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sph {

struct RunOutputs {
    std::string status; // run.json "status"; "missing" without a readable run.json
    std::uint64_t steps = 0;
    std::size_t particles = 0;
    double wall_s; // run.json "wall_s"; NaN when absent
    double dt_avg; // mean of stats.csv "dt" over frames, s
    double
        density_error_avg_pct; // mean of density_error_avg_pct over frames 1.. (0 is the lattice)
    double density_error_max_pct; // largest density_error_max_pct of any frame
    nlohmann::json scene;         // the scene as resolved
};

// Never throws: whatever is missing stays NaN, 0 or empty.
RunOutputs read_run_outputs(const std::filesystem::path& run);

// stats.csv "time" (s) by frame number; NaN for a frame it lacks. Throws
// std::runtime_error when stats.csv cannot be read.
std::vector<double> frame_times(const std::filesystem::path& run);

// The scene values the metrics need, from run.json's resolved "scene".
struct SceneFacts {
    int dimension = 2;
    double spacing = 0;      // m
    double rest_density = 0; // kg/m^3
    double gravity = 0;      // |g|, m/s^2; 0 without the gravity effect
    double viscosity = 0;    // mu of the viscosity effect, Pa.s; 0 without it
    std::vector<double> domain_min, domain_max;
    std::vector<double> block_min, block_max; // the first fluid block
};

// Throws std::runtime_error naming the key that is missing.
SceneFacts scene_facts(const nlohmann::json& scene);

} // namespace sph
