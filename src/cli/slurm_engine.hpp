#pragma once
// `--engine slurm`: a plan as one Slurm job array (one array task per run,
// SLURM_ARRAY_TASK_ID picks it) and its collect step as a job that waits for
// the array (docs/cluster.md). Slurm schedules; sphclip only writes the
// scripts and calls sbatch.

#include "cli/plan_folder.hpp"

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sph {

struct SlurmOptions {
    std::string partition;                // --partition; empty: the site's default
    std::string time;                     // --time, [D-]HH:MM:SS or minutes; empty: the default
    int cpus_per_task = 0;                // --cpus-per-task; 0: the site's default (1)
    int max_running = 0;                  // --max-running: the array's %K; 0: no limit
    std::vector<std::string> sbatch_args; // --sbatch-arg, one #SBATCH line each
};

// Throws InputError naming the flag: a --time Slurm would not read, a
// --partition that is no partition name, an --sbatch-arg over lines.
void check_slurm_options(const SlurmOptions& options);

nlohmann::json slurm_options_json(const SlurmOptions& options);
SlurmOptions slurm_options_from_json(const nlohmann::json& record);

// "0-3,7,9-10%K": Slurm's --array for these indices (sorted, distinct).
std::string array_spec(const std::vector<std::size_t>& indices, int max_running);

// The array's and the collect job's scripts (PLAN/slurm/array.sbatch,
// collect.sbatch) as text.
std::string array_script(const Plan& plan, const SlurmOptions& options,
                         const std::vector<std::size_t>& indices);
std::string collect_script(const Plan& plan, const SlurmOptions& options);

// Writes both scripts; unless `dry_run`, submits the array with
// `sbatch --parsable` and the collect job with --dependency=afterany on it,
// and appends both job ids to PLAN/slurm/submissions.json. sbatch is
// $SPHCLIP_SBATCH when set, else found in PATH. Returns 0, or exit_scheduler
// (5) after saying why when sbatch cannot be started or refuses a job.
int submit_to_slurm(const Plan& plan, const SlurmOptions& options,
                    const std::vector<std::size_t>& indices, bool dry_run);

} // namespace sph
