#include "cli/run_child.hpp"

#include "cli/child_process.hpp"
#include "cli/exit_codes.hpp"
#include "cli/stop_signals.hpp"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fmt/format.h>
#include <optional>
#include <thread>

namespace sph {

namespace fs = std::filesystem;

namespace {

void clear_earlier_outputs(const fs::path& out) {
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec)
        throw std::runtime_error(fmt::format("cannot create {}: {}", out.string(), ec.message()));
    fs::remove(out / "run.json", ec);
    fs::remove(out / "stats.csv", ec);
    fs::remove_all(out / "particles", ec);
}

} // namespace

std::vector<std::string> child_run_arguments(const ChildRunRequest& request) {
    std::vector<std::string> args{
        "run",   request.scene.string(), "--no-png", "--no-mp4", "--quiet",
        "--out", request.out.string()};
    for (const auto& set : request.sets) {
        args.push_back("--set");
        args.push_back(set);
    }
    if (request.export_csv) {
        args.push_back("--export");
        args.push_back("csv");
    }
    if (request.threads > 0) {
        args.push_back("--threads");
        args.push_back(std::to_string(request.threads));
    }
    return args;
}

ChildBatch run_children(const std::vector<ChildRunRequest>& requests, int jobs,
                        const std::function<void(std::size_t, const ChildRunResult&)>& finished) {
    using clock = std::chrono::steady_clock;
    const std::string program = self_executable().string();
    const StopSignals stop_signals;
    // Runs side by side share the cores: an OpenMP thread that spins while
    // it waits takes a core from another run. The user's choice stands.
    if (jobs > 1)
        setenv("OMP_WAIT_POLICY", "passive", 0);

    struct Running {
        std::size_t index;
        pid_t pid;
        clock::time_point start;
    };
    std::vector<Running> running;
    ChildBatch batch;
    batch.runs.resize(requests.size());
    std::size_t next = 0;
    bool first_checked = requests.empty();
    bool stopping = false;

    while (next < requests.size() || !running.empty()) {
        if (StopSignals::received() != 0 && !stopping) {
            stopping = batch.interrupted = true;
            for (const auto& r : running)
                kill(r.pid, SIGTERM);
        }
        // Reap the children that have ended.
        for (std::size_t k = 0; k < running.size();) {
            const auto code = child_exit_code(running[k].pid, false);
            if (!code) {
                ++k;
                continue;
            }
            auto& result = batch.runs[running[k].index];
            result.exit_code = *code;
            result.measured_wall_s =
                std::chrono::duration<double>(clock::now() - running[k].start).count();
            if (running[k].index == 0 && *code == exit_bad_input) {
                batch.bad_input = true;
                stopping = true;
            }
            if (running[k].index == 0)
                first_checked = true;
            if (finished)
                finished(running[k].index, result);
            running.erase(running.begin() + std::ptrdiff_t(k));
        }
        // The first run is past its input checks once it has written run.json.
        if (!first_checked && !running.empty() && running.front().index == 0 &&
            fs::exists(requests[0].out / "run.json"))
            first_checked = true;

        const bool may_start = next == 0 || first_checked;
        while (!stopping && may_start && next < requests.size() &&
               int(running.size()) < std::max(jobs, 1)) {
            const auto& request = requests[next];
            clear_earlier_outputs(request.out);
            auto args = child_run_arguments(request);
            args.insert(args.begin(), program);
            auto& result = batch.runs[next];
            result.log = request.out / "run.log";
            running.push_back(
                {next, start_child(this_program, args, result.log, false), clock::now()});
            result.started = true;
            ++next;
            if (!first_checked)
                break;
        }
        if (stopping && running.empty())
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return batch;
}

} // namespace sph
