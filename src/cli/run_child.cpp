#include "cli/run_child.hpp"

#include "cli/child_process.hpp"
#include "cli/exit_codes.hpp"
#include "cli/stop_signals.hpp"

#include <algorithm>
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

using Clock = std::chrono::steady_clock;
using Finished = std::function<void(std::size_t, const ChildRunResult&)>;

// A batch in progress: the children running, the next request to start,
// and whether the first run is past its input checks.
class ChildPool {
  public:
    ChildPool(const std::vector<ChildRunRequest>& requests, int jobs, const Finished& finished)
        : requests_(requests), jobs_(std::max(jobs, 1)), finished_(finished),
          program_(self_executable().string()), first_checked_(requests.empty()) {
        batch_.runs.resize(requests.size());
    }

    bool busy() const { return next_ < requests_.size() || !running_.empty(); }
    // Stopping, and every child started has ended.
    bool stopped() const { return stopping_ && running_.empty(); }

    // Asks the running children to stop (they keep what they have); no other starts.
    void interrupt() {
        if (stopping_)
            return;
        stopping_ = batch_.interrupted = true;
        for (const auto& r : running_)
            kill(r.pid, SIGTERM);
    }

    // Records the children that have ended.
    void reap() {
        for (std::size_t k = 0; k < running_.size();) {
            const auto code = child_exit_code(running_[k].pid, false);
            if (!code) {
                ++k;
                continue;
            }
            const std::size_t index = running_[k].index;
            auto& result = batch_.runs[index];
            result.exit_code = *code;
            result.measured_wall_s =
                std::chrono::duration<double>(Clock::now() - running_[k].start).count();
            if (index == 0 && *code == exit_bad_input) {
                batch_.bad_input = true;
                stopping_ = true;
            }
            if (index == 0)
                first_checked_ = true;
            if (finished_)
                finished_(index, result);
            running_.erase(running_.begin() + std::ptrdiff_t(k));
        }
    }

    // Starts children up to --jobs: only the first until it is past its
    // input checks (it has written run.json).
    void start_more() {
        if (!first_checked_ && !running_.empty() && running_.front().index == 0 &&
            fs::exists(requests_[0].out / "run.json"))
            first_checked_ = true;
        const bool may_start = next_ == 0 || first_checked_;
        while (!stopping_ && may_start && next_ < requests_.size() &&
               int(running_.size()) < jobs_) {
            start(next_++);
            if (!first_checked_)
                break;
        }
    }

    const ChildBatch& batch() const { return batch_; }

  private:
    void start(std::size_t index) {
        const auto& request = requests_[index];
        clear_earlier_outputs(request.out);
        auto args = child_run_arguments(request);
        args.insert(args.begin(), program_);
        auto& result = batch_.runs[index];
        result.log = request.out / "run.log";
        running_.push_back(
            {index, start_child(this_program, args, result.log, false), Clock::now()});
        result.started = true;
    }

    struct Running {
        std::size_t index;
        pid_t pid;
        Clock::time_point start;
    };
    const std::vector<ChildRunRequest>& requests_;
    const int jobs_;
    const Finished& finished_;
    const std::string program_;
    std::vector<Running> running_;
    ChildBatch batch_;
    std::size_t next_ = 0;
    bool first_checked_;
    bool stopping_ = false;
};

} // namespace

std::vector<std::string> child_run_arguments(const ChildRunRequest& request) {
    std::vector<std::string> args{"run", request.scene.string()};
    if (!request.frames)
        args.push_back("--no-png");
    if (!request.video)
        args.push_back("--no-mp4");
    args.insert(args.end(), {"--quiet", "--out", request.out.string()});
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
                        const Finished& finished) {
    const StopSignals stop_signals;
    // Runs side by side share the cores: an OpenMP thread that spins while
    // it waits takes a core from another run. The user's choice stands.
    if (jobs > 1)
        setenv("OMP_WAIT_POLICY", "passive", 0);
    ChildPool pool(requests, jobs, finished);
    while (pool.busy()) {
        if (StopSignals::received() != 0)
            pool.interrupt();
        pool.reap();
        pool.start_more();
        if (pool.stopped())
            break;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return pool.batch();
}

} // namespace sph
