#pragma once
// `sphclip validate [CASE...]`: runs shipped scenes whose outcome is known and
// scores them (docs/validation.md).

#include "cli/plan_engine.hpp"
#include "cli/plan_folder.hpp"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sph {

struct ValidateOptions {
    std::vector<std::string> cases; // empty: every case
    std::string out = "out/validate";
    std::vector<std::string> sets; // --set KEY=VALUE, for every case
    int jobs = 1;                  // cases run at once
    int threads = 0;               // per run; 0: all cores, or 1 when jobs > 1
    std::string scenes_dir;        // empty: found (data_folders.hpp)
    std::string reference_dir;     // empty: found
    EngineOptions engine;          // --engine and its options (plan_engine.hpp)
};

// Adds the `validate` subcommand to `app`; parsing fills `options`.
CLI::App* add_validate_command(CLI::App& app, ValidateOptions& options);

// Writes the plan into --out and runs it with the engine, then collects
// (collect_validate). Prints one summary line per case; returns 0 when every case ran, 3 when
// one was unstable, 130 when interrupted, 1 for another failure. Throws
// InputError for an unknown case or a missing scene or reference folder.
int validate_command(const ValidateOptions& options);

// Scores the plan's finished runs (summary.csv, CASE/ tables and plots) and
// returns as validate does: 0, 3 unstable, 130 interrupted, 2, 1.
int collect_validate(const Plan& plan);

// completed, unstable, interrupted, bad_input, failed, not_run.
std::string validate_run_status(const ChildRunResult& result);

} // namespace sph
