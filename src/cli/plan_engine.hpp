#pragma once
// Which engine runs a plan (plan_folder.hpp): `--engine local` (the
// default: child processes here, --jobs at a time, then collect) or
// `--engine slurm` (a job array and a collect job; slurm_engine.hpp). The
// options are shared by study, validate, batch and run-plan.

#include "cli/plan_folder.hpp"
#include "cli/slurm_engine.hpp"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sph {

struct EngineOptions {
    std::string engine = "local"; // local, slurm
    bool dry_run = false;         // write the plan (and scripts), run nothing
    SlurmOptions slurm;
};

// --engine, --dry-run, --partition, --time, --cpus-per-task, --max-running,
// --sbatch-arg.
void add_engine_options(CLI::App* cmd, EngineOptions& options);

// Before anything is written: throws InputError naming the flag for a Slurm
// option without --engine slurm, or one Slurm would refuse.
void check_engine_options(const EngineOptions& options);

// --threads per run: as given; else under Slurm --cpus-per-task (1 without
// it: a task must not take a node's every core), else threads_per_run.
int plan_threads(int threads, int jobs, const EngineOptions& options);

// How plan.json records the engine, for run-plan and collect --resubmit.
nlohmann::json engine_record(const EngineOptions& options, int jobs);
EngineOptions engine_from_record(const nlohmann::json& record);
int jobs_from_record(const nlohmann::json& record);

// Runs the plan's runs `indices`. Local: prints `intro`, runs them (each
// run's exit record as it ends), then collects; returns what collect
// returns, 130 when interrupted, 2 when the first run found its input bad.
// Slurm: submits them and the collect job (submit_to_slurm). --dry-run:
// nothing runs.
int execute_plan(const Plan& plan, const EngineOptions& options, int jobs,
                 const std::vector<std::size_t>& indices, const std::string& intro);

// Every index of the plan.
std::vector<std::size_t> all_runs(const Plan& plan);

} // namespace sph
