#include "cli/stage_report.hpp"

#include <fmt/format.h>

namespace sph {

std::vector<StageRow> stage_rows(const StageTimes& simulation, const StageTimes& after,
                                 double wall_seconds, std::uint64_t particle_steps,
                                 const StageTimes& overlapped, const SolveWork& solves,
                                 std::uint64_t steps) {
    // The solves' work by their stage's name.
    const auto work_of = [&](std::string_view name) -> std::pair<std::uint64_t, std::uint64_t> {
        if (name == stage_name(Stage::pressure_solve))
            return {solves.pressure, solves.pressure_iterations};
        if (name == stage_name(Stage::divergence_solve))
            return {solves.divergence, solves.divergence_iterations};
        return {0, 0};
    };
    std::vector<StageRow> rows;
    for (const StageTimes* times : {&simulation, &after, &overlapped})
        for (const auto& e : times->entries()) {
            if (e.within) {
                rows.push_back(
                    {std::string(e.name), 0, 0, 0, false, std::string(stage_name(*e.within))});
                continue;
            }
            if (e.seconds <= 0)
                continue;
            rows.push_back({std::string(e.name), e.seconds,
                            wall_seconds > 0 ? e.seconds / wall_seconds : 0,
                            particle_steps ? e.seconds * 1e9 / double(particle_steps) : 0,
                            times == &overlapped, std::string()});
            const auto [particle_iterations, iterations] = work_of(e.name);
            if (particle_iterations > 0) {
                rows.back().ns_per_particle_iteration =
                    e.seconds * 1e9 / double(particle_iterations);
                rows.back().iterations_per_step = steps ? double(iterations) / double(steps) : 0;
            }
        }
    return rows;
}

nlohmann::json stages_json(const std::vector<StageRow>& rows) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& r : rows) {
        if (!r.within.empty()) {
            list.push_back({{"name", r.name}, {"within", r.within}});
            continue;
        }
        list.push_back({{"name", r.name},
                        {"seconds", r.seconds},
                        {"share", r.share},
                        {"ns_per_particle_step", r.ns_per_particle_step}});
        if (r.overlapped)
            list.back()["overlapped"] = true;
        if (r.ns_per_particle_iteration > 0) {
            list.back()["ns_per_particle_iteration"] = r.ns_per_particle_iteration;
            list.back()["iterations_per_step"] = r.iterations_per_step;
        }
    }
    return list;
}

std::string stages_table(const std::vector<StageRow>& rows) {
    std::string out = fmt::format("{:<24} {:>10} {:>7} {:>14}\n", "stage", "seconds", "share",
                                  "ns/particle-step");
    bool any_overlapped = false;
    for (const auto& r : rows) {
        if (!r.within.empty()) {
            out += fmt::format("{:<24} {:>10}\n", r.name, "in " + r.within);
            continue;
        }
        out += fmt::format("{:<24} {:>10.3f} {:>6.1f}% {:>14.1f}",
                           r.overlapped ? r.name + " *" : r.name, r.seconds, 100 * r.share,
                           r.ns_per_particle_step);
        if (r.ns_per_particle_iteration > 0)
            out += fmt::format("  ({:.1f} iterations a step, {:.1f} ns/particle-iteration)",
                               r.iterations_per_step, r.ns_per_particle_iteration);
        out += "\n";
        any_overlapped = any_overlapped || r.overlapped;
    }
    if (any_overlapped)
        out += "* on a worker thread, at the same time as the stages above\n";
    return out;
}

} // namespace sph
