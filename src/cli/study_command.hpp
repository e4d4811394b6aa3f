#pragma once
// `sphclip study SCENE --vary KEY=V1,V2...`: runs a scene for every
// combination of the varied values and weighs accuracy against cost
// (docs/validation.md, "Studies").

#include "cli/plan_engine.hpp"
#include "cli/plan_folder.hpp"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sph {

struct StudyOptions {
    std::string scene;
    std::vector<std::string> vary; // --vary KEY=V1,V2,...
    std::vector<std::string> sets; // --set KEY=VALUE, for every run, before the varied values
    double duration = 0;           // --duration S: --set duration=S; 0: the scene's
    double fps = 0;                // --fps N: --set fps=N; 0: the scene's
    std::string metric;            // com, kinetic_energy, surface_height; empty: com
    std::string reference;         // finest, a validation case; empty: by the scene's name
    std::string out;               // empty: out/study_<scene name>
    int jobs = 1;
    int threads = 0; // per run; 0: all cores, or 1 when jobs > 1
    std::string reference_dir;
    std::string command_line; // recorded in study.md
    EngineOptions engine;     // --engine and its options (plan_engine.hpp)
};

// Adds the `study` subcommand to `app`; parsing fills `options`.
CLI::App* add_study_command(CLI::App& app, StudyOptions& options);

// Writes the plan into --out, then runs it with the engine and collects
// (collect_study). Returns 0 when every run was tried (unstable or failed
// runs are rows that say so), 2 when the first run finds the scene or a
// --set bad, 130 when interrupted. Throws InputError for a bad --vary or
// --reference. Under --engine slurm it returns once submitted.
int study_command(const StudyOptions& options);

// study.csv, study.md and study.png from the runs' outputs and exit
// records; 0.
int collect_study(const Plan& plan);

// ok, unstable, failed, interrupted, not_run: a run's status in study.csv.
std::string study_run_status(const ChildRunResult& result);

} // namespace sph
