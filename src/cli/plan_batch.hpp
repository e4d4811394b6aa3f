#pragma once
// `sphclip batch SCENE... | --list FILE`: every scene into a clip of its own,
// as a plan (plan_folder.hpp) that any engine runs; batch.csv says how each
// run ended (docs/cluster.md).

#include "cli/plan_engine.hpp"
#include "cli/plan_folder.hpp"

#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sph {

struct BatchOptions {
    std::vector<std::string> scenes;
    std::string list;              // --list FILE: one scene a line, # comments
    std::string out = "out/batch"; // runs/NN_<scene name>/ inside
    std::vector<std::string> sets; // --set for every run
    int jobs = 1;
    int threads = 0;
    bool no_png = false, no_mp4 = false; // passed on to each run
    bool export_csv = false;             // --export csv
    EngineOptions engine;
};

CLI::App* add_batch_command(CLI::App& app, BatchOptions& options);

// Writes the plan and runs it with the engine, then collects. Throws
// InputError for a missing scene or list (nothing is written then).
int batch_command(const BatchOptions& options);

// batch.csv: one row per run (scene, status, exit code, particles, steps,
// wall time, the last frame's state hash, folder). Returns 0 when every run
// completed, else as validate: 130, 2, 3 or 1 by the worst run.
int collect_batch(const Plan& plan);

// ok, unstable, no_gl_context, bad_input, interrupted, failed, not_run.
std::string batch_run_status(const ChildRunResult& result);

} // namespace sph
