#pragma once
// The plan commands (docs/cluster.md):
//   sphclip collect PLAN [--resubmit [--dry-run]]   results of the runs so far
//   sphclip run-plan PLAN [--engine ...] [--jobs N] runs a written plan
//   sphclip plan-task PLAN INDEX                    runs one run (an array task)

#include "cli/plan_engine.hpp"
#include "cli/plan_folder.hpp"

#include <string>

namespace CLI {
class App;
}

namespace sph {

// The kind's results from what the runs left (study.csv/md/png, validate's
// summary.csv and scores, batch.csv), then one line per run that did not
// exit 0, with its exit code. Returns the kind's collect code.
int collect_plan(const Plan& plan);

struct PlanCommandOptions {
    std::string folder;
    std::string index; // plan-task
    bool resubmit = false;
    int jobs = 0; // run-plan, collect --resubmit local; 0: as recorded
    EngineOptions engine;
};

struct PlanCommands {
    CLI::App* collect = nullptr;
    CLI::App* run_plan = nullptr;
    CLI::App* plan_task = nullptr;
};

PlanCommands add_plan_commands(CLI::App& app, PlanCommandOptions& options);

// collect: the kind's code; with --resubmit, what running the unfinished
// runs again returns (0 with nothing to send).
int collect_command(const PlanCommandOptions& options);
// run-plan: as execute_plan, with the engine given or else as recorded.
int run_plan_command(const PlanCommandOptions& options, bool engine_given);
// plan-task: the run's own exit code; 2 for a bad INDEX or plan.
int plan_task_command(const PlanCommandOptions& options);

} // namespace sph
