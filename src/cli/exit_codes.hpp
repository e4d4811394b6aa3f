#pragma once
// The program's exit codes (README, "Exit codes"). Scripts rely on them.

namespace sph {

enum ExitCode : int {
    exit_success = 0,
    exit_failure = 1,       // anything else: disk full, internal error
    exit_bad_input = 2,     // command line, scene file, --set, output folder
    exit_unstable = 3,      // a step failed the watchdog even halved (NaN, blow-up, collapse)
    exit_no_gl_context = 4, // no headless OpenGL context could be made
    exit_scheduler = 5,     // --engine slurm: sbatch missing, or it refused a job
    exit_interrupted = 130, // SIGINT or SIGTERM: outputs so far are finalised
};

} // namespace sph
