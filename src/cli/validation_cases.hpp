#pragma once
// The cases of `sphclip validate`: shipped scenes (scenes/CASE.json) whose
// outcome is known, and how a finished run of one is scored. `study` scores
// its runs the same way when its scene is one of them.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

enum class CaseKind {
    hydrostatic, // a settled tank against p = rho0 |g| depth
    dam_break,   // the surge front against Martin & Moyce (1952)
    spreading,   // a viscous column's front against Huppert's (1982) gravity current
};

struct ValidationCase {
    std::string name; // also the scene's file stem
    CaseKind kind;
    // --set overrides the case runs with, before the user's (which win).
    std::vector<std::string> sets;
};

// hydrostatic_2d, hydrostatic_3d, dam_break_2d, dam_break_3d (the seed's viscous fluid),
// dam_break_water_2d, dam_break_water_2d_dfsph, dam_break_water_3d, dam_break_water_3d_dfsph
// (water, wcsph and dfsph), honey_spread_2d.
const std::vector<ValidationCase>& validation_cases();

// Null for a name that is no case.
const ValidationCase* find_validation_case(std::string_view name);

// The cases' names, "a, b, c", for messages.
std::string validation_case_names();

// The reference table a case needs in the reference folder; empty for none.
std::string reference_file(const ValidationCase& c);

// What a case's error measures, e.g. "mean |ΔZ| vs Martin & Moyce (1952)".
std::string case_error_name(const ValidationCase& c);

struct CaseScore {
    double error = 0;       // the headline figure: mean |dZ|, the pressure RMS error in %, or
                            // the front's mean error in %
    std::string error_name; // how study.md and plots name it
    std::string figures;    // "mean|dZ|=0.083  max|dZ|=0.15", for the summary line
    nlohmann::json metrics; // every figure by name (metrics.json)
    bool pass = false;      // within the documented tolerances
};

// Scores the completed run in `run` and writes the comparison CSV(s) into
// `folder` (and the plot, when `plot`; `label` goes into its title).
// Throws std::runtime_error when the run's outputs are missing or unusable.
CaseScore score_case(const ValidationCase& c, const std::filesystem::path& run,
                     const std::filesystem::path& folder,
                     const std::filesystem::path& reference_folder, bool plot,
                     const std::string& label);

} // namespace sph
