#include "cli/stage_report.hpp"

#include <fmt/format.h>

namespace sph {

std::vector<StageRow> stage_rows(const StageTimes& simulation, const StageTimes& after,
                                 double wall_seconds, std::uint64_t particle_steps,
                                 const StageTimes& overlapped) {
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
        out += fmt::format("{:<24} {:>10.3f} {:>6.1f}% {:>14.1f}\n",
                           r.overlapped ? r.name + " *" : r.name, r.seconds, 100 * r.share,
                           r.ns_per_particle_step);
        any_overlapped = any_overlapped || r.overlapped;
    }
    if (any_overlapped)
        out += "* on a worker thread, at the same time as the stages above\n";
    return out;
}

} // namespace sph
