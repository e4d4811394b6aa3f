#pragma once
// A plan: the runs of a `study`, `validate` or `batch` written down before
// any of them starts, so that any engine can run them (docs/cluster.md).
//
//   PLAN/plan.json           the manifest: kind, program, every run's
//                            request and command line, what collect needs
//   PLAN/plan/NN/command.json  run NN's argv (program first)
//   PLAN/plan/NN/scene.json    run NN's scene as resolved (its --set applied)
//   PLAN/plan/NN/exit.json     once run NN has ended: its exit code
//
// A run is addressed by its index (a Slurm array task's id). Its outputs
// go where the command has always put them (runs/..., CASE/run).

#include "cli/run_child.hpp"

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sph {

struct PlanRun {
    std::string name;        // in progress lines: "run 00_fps=10", "dam_break_2d"
    ChildRunRequest request; // absolute scene and out paths
};

struct Plan {
    std::string kind;              // study, validate, batch
    std::filesystem::path folder;  // absolute
    std::filesystem::path program; // the sphclip that runs the tasks
    std::vector<PlanRun> runs;
    nlohmann::json details; // what collect needs, by kind
    nlohmann::json engine;  // how it was last run: {"name": "local", "jobs": N} or slurm options
};

// The folder of run `index`'s plan files: plan/NN (at least two digits).
std::filesystem::path task_folder(const Plan& plan, std::size_t index);

// Writes plan.json and each run's command.json and scene.json, and removes
// exit records an earlier plan in the folder left. When `strict`, a scene
// that cannot be resolved throws its InputError (nothing is submitted then);
// otherwise its scene.json is left out and the run reports the problem.
void write_plan(const Plan& plan, bool strict);

// Rewrites plan.json alone (after the engine record changed).
void write_manifest(const Plan& plan);

// Throws InputError naming PLAN/plan.json and the field when it is missing
// or not a plan.
Plan read_plan(const std::filesystem::path& folder);

// exit.json: the exit code, the wall time measured around the run, where it ran.
void write_run_record(const Plan& plan, std::size_t index, const ChildRunResult& result);
void remove_run_record(const Plan& plan, std::size_t index);

// A run's result as its exit.json says; started is false without one. The
// log is the run's out/run.log.
ChildRunResult read_run_record(const Plan& plan, std::size_t index);

// The indices of runs that have no exit record or did not exit 0.
std::vector<std::size_t> unfinished_runs(const Plan& plan);

} // namespace sph
