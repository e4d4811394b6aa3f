#include "cli/plan_engine.hpp"

#include "cli/batch_runs.hpp"
#include "cli/collect_command.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plan_batch.hpp"
#include "cli/study_command.hpp"
#include "cli/validate_command.hpp"
#include "scene/input_error.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <numeric>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using StatusOf = std::string (*)(const ChildRunResult&);

// The progress lines name a run's status as the command always has.
StatusOf status_for(const std::string& kind) {
    if (kind == "study")
        return study_run_status;
    if (kind == "validate")
        return validate_run_status;
    return batch_run_status;
}

int run_locally(const Plan& plan, int jobs, const std::vector<std::size_t>& indices,
                const std::string& intro) {
    std::vector<ChildRunRequest> requests;
    std::vector<std::string> names;
    for (const std::size_t i : indices) {
        remove_run_record(plan, i);
        requests.push_back(plan.runs[i].request);
        names.push_back(plan.runs[i].name);
    }
    const auto batch = run_batch(
        intro, requests, jobs, names, status_for(plan.kind),
        [&](std::size_t k, const ChildRunResult& r) { write_run_record(plan, indices[k], r); });
    if (!batch)
        return exit_bad_input;
    const int code = collect_plan(plan);
    return batch->interrupted ? exit_interrupted : code;
}

} // namespace

void add_engine_options(CLI::App* cmd, EngineOptions& options) {
    cmd->add_option("--engine", options.engine,
                    "Who runs the plan: local (child processes here) or slurm (a job array)")
        ->check(CLI::IsMember({"local", "slurm"}))
        ->capture_default_str();
    cmd->add_flag("--dry-run", options.dry_run,
                  "Write the plan (and the Slurm scripts), run and submit nothing");
    cmd->add_option("--partition", options.slurm.partition, "Slurm partition (--engine slurm)");
    cmd->add_option("--time", options.slurm.time,
                    "Slurm time limit per run, HH:MM:SS or D-HH:MM:SS (--engine slurm)");
    cmd->add_option("--cpus-per-task", options.slurm.cpus_per_task,
                    "Cores per run, and its --threads (--engine slurm)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--max-running", options.slurm.max_running,
                    "Runs of the array at once, its %K (--engine slurm)")
        ->check(CLI::Range(1, 1000000));
    cmd->add_option("--sbatch-arg", options.slurm.sbatch_args,
                    "A site's sbatch option, one #SBATCH line: --sbatch-arg=--account=proj "
                    "(repeatable, --engine slurm)")
        ->type_name("ARG")
        ->allow_extra_args(false);
}

void check_engine_options(const EngineOptions& options) {
    if (options.engine != "slurm") {
        const auto& s = options.slurm;
        const std::pair<bool, const char*> slurm_only[] = {
            {!s.partition.empty(), "--partition"},
            {!s.time.empty(), "--time"},
            {s.cpus_per_task > 0, "--cpus-per-task"},
            {s.max_running > 0, "--max-running"},
            {!s.sbatch_args.empty(), "--sbatch-arg"}};
        for (const auto& [given, flag] : slurm_only)
            if (given)
                throw InputError("command line", flag, "only with --engine slurm");
        return;
    }
    check_slurm_options(options.slurm);
}

int plan_threads(int threads, int jobs, const EngineOptions& options) {
    if (threads)
        return threads;
    if (options.engine == "slurm")
        return options.slurm.cpus_per_task > 0 ? options.slurm.cpus_per_task : 1;
    return threads_per_run(threads, jobs);
}

json engine_record(const EngineOptions& options, int jobs) {
    if (options.engine == "slurm")
        return slurm_options_json(options.slurm);
    return {{"name", "local"}, {"jobs", jobs}};
}

EngineOptions engine_from_record(const json& record) {
    EngineOptions options;
    options.engine = record.value("name", "local");
    if (options.engine == "slurm")
        options.slurm = slurm_options_from_json(record);
    return options;
}

int jobs_from_record(const json& record) {
    return std::max(1, record.value("jobs", 1));
}

std::vector<std::size_t> all_runs(const Plan& plan) {
    std::vector<std::size_t> indices(plan.runs.size());
    std::iota(indices.begin(), indices.end(), std::size_t(0));
    return indices;
}

int execute_plan(const Plan& plan, const EngineOptions& options, int jobs,
                 const std::vector<std::size_t>& indices, const std::string& intro) {
    if (options.engine == "slurm")
        return submit_to_slurm(plan, options.slurm, indices, options.dry_run);
    if (options.dry_run) {
        fmt::print("{}: --dry-run: the plan of {} run(s) is in {}; `sphclip run-plan {}` runs "
                   "it\n",
                   plan.kind, plan.runs.size(), (plan.folder / "plan.json").string(),
                   plan.folder.string());
        return exit_success;
    }
    return run_locally(plan, jobs, indices, intro);
}

} // namespace sph
