#pragma once
// Runs of a scene as `sphclip run` child processes, several at once: how
// `validate` and `study` simulate.

#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace sph {

struct ChildRunRequest {
    std::filesystem::path scene;
    std::filesystem::path out;     // the run's --out folder; its log is out/run.log
    std::vector<std::string> sets; // "KEY=VALUE", passed on as --set in order
    bool export_csv = false;       // --export csv (particle files per frame)
    int threads = 0;               // --threads; 0: the child's default (all cores)
    bool frames = false;           // PNG frames (else --no-png); a batch's clips have them
    bool video = false;            // clip.mp4 (else --no-mp4)
};

// `run SCENE [--no-png] [--no-mp4] --quiet --out DIR [--set K=V]... [--export csv] [--threads N]`
std::vector<std::string> child_run_arguments(const ChildRunRequest& request);

struct ChildRunResult {
    bool started = false;
    int exit_code = -1;         // the child's (README, "Exit codes")
    double measured_wall_s = 0; // from start to exit, as seen from here
    std::filesystem::path log;  // the child's output and errors
};

struct ChildBatch {
    std::vector<ChildRunResult> runs; // one per request
    bool interrupted = false;         // SIGINT or SIGTERM arrived
    bool bad_input = false;           // the first run exited 2: nothing else was started
};

// Runs every request, at most `jobs` at a time. The first run starts alone,
// and the others only once it is past its input checks (its run.json exists,
// or it ended with another code than 2): a bad scene or --set fails once, not
// once per run. Outputs of an earlier run in a request's folder (run.json,
// stats.csv, particles/) are removed first, so none is mistaken for this
// run's. `finished(i, result)` is called as run i ends (a progress line). On SIGINT or SIGTERM the
// running children are asked to stop (they keep what they have) and no
// other starts. With jobs > 1 the children get OMP_WAIT_POLICY=passive
// unless it is set.
ChildBatch run_children(const std::vector<ChildRunRequest>& requests, int jobs,
                        const std::function<void(std::size_t, const ChildRunResult&)>& finished);

} // namespace sph
