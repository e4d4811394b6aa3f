#pragma once
// How many OpenMP threads a run steps with when the user gave no --threads
// (issue 22, item 4; docs/benchmarks.md, "Busy machines").
//
// On a machine another process shares, every thread but one may wait at each
// barrier for a thread the scheduler has set aside: with one busy process on
// 2 cores, 2 threads stepped a 2D dam break at 0.30x of 1 thread (libgomp's
// spin count 10,000), 0.84x when the waiting threads sleep at once. No wait
// policy makes 2 threads worth it there, and on a quiet machine they are
// worth 1.6-1.8x. So the run measures: it steps with a thread count for a
// window of wall time, now and then tries the next count up or down for one
// window, and keeps whichever cost less per particle-step. Every thread count
// gives the same bits (the project's determinism), so the choice changes only
// the time.
//
// The counts tried are the ladder max, max/2, ..., 1. A try that loses is
// tried again after twice as many windows (up to max_interval), so a quiet
// machine pays little for it; a window that costs far more than the last one
// (a competing job started) makes the next window a try, once at least
// first_interval windows have passed since the last try. A try that is
// plainly losing ends after a quarter of its window.
//
// Where the kernel's count of runnable threads describes this process's
// cores (parallel/free_cores.hpp), the tuner asks it first: the run starts
// with no more threads than there are free cores, and a try of more threads
// waits while the cores it would need are busy, so a machine busy from the
// start or for a long while costs no tries at all.

#include "parallel/free_cores.hpp"

#include <chrono>
#include <cstdint>
#include <omp.h>
#include <vector>

namespace sph::parallel {

class ThreadCountTuner {
  public:
    struct Settings {
        double window_s = 0.25;    // wall time of one measurement of the count kept
        double try_window_s = 0.1; // ... of a try, and of the first window
        int first_interval = 4;    // windows between tries, at first and after a change
        int max_interval = 128;    // ... at most, after tries that lost
        double margin = 0.08;      // a try must cost this fraction less to win
        double slowdown = 1.35;    // a window this much dearer than the last: try now
        // A try that after this fraction of its window already costs
        // abort_slowdown times the kept count's last window has lost: it
        // ends there (on a busy machine a try of more threads costs 3x).
        double abort_after = 0.25;
        double abort_slowdown = 1.5;
    };

    // max_threads >= 1: the most threads a step may use. free_cores, where
    // given, says how many cores other processes leave free (-1: unknown).
    explicit ThreadCountTuner(int max_threads, FreeCores free_cores = {})
        : ThreadCountTuner(max_threads, Settings{}, std::move(free_cores)) {}
    ThreadCountTuner(int max_threads, Settings settings, FreeCores free_cores = {});

    // The thread count for the next step.
    int threads() const { return ladder_[active_]; }
    // One step's wall time and the particle-steps it made (particles moved).
    void record(double seconds, std::uint64_t particle_steps);
    // One step at the chosen count, timed and recorded: step() returns the
    // particle-steps it made.
    template <class Step>
    void step(const Step& step) {
        omp_set_num_threads(threads());
        const auto start = std::chrono::steady_clock::now();
        const std::uint64_t made = step();
        record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
               made);
    }

    // Steps taken at each count of the ladder, for run.json.
    struct Use {
        int threads = 0;
        std::uint64_t steps = 0;
        double seconds = 0;
    };
    std::vector<Use> uses() const;
    // Times the count in use changed.
    int changes() const { return changes_; }
    // Tries of more threads not made because the kernel counted their cores busy.
    int tries_skipped() const { return tries_skipped_; }
    // The count the run started with, below the most where cores were busy.
    int first_threads() const { return ladder_[first_]; }
    // Whether the kernel's count of free cores was given to the tuner.
    bool free_cores_known() const { return bool(free_cores_); }

  private:
    // The window just measured: its cost per particle-step, at ladder_[active_].
    void end_window(double cost);
    void start_try(int index);

    Settings settings_;
    FreeCores free_cores_;             // empty: the kernel's count is not ours
    std::vector<int> ladder_;          // max, max/2, ..., 1
    std::vector<std::uint64_t> steps_; // per ladder entry
    std::vector<double> seconds_;      // per ladder entry
    int active_ = 0;                   // ladder index stepping now
    int kept_ = 0;                     // ladder index chosen
    bool trying_ = false;              // the current window is a try
    double kept_cost_ = 0;             // s per particle-step of kept_'s last window
    int interval_ = 0;                 // windows between tries
    int windows_since_try_ = 0;        // kept_'s windows since the last try
    int next_direction_ = 1;           // the next try: +1 fewer threads, -1 more
    double window_seconds_ = 0;        // the window under way
    std::uint64_t window_particle_steps_ = 0;
    int changes_ = 0;
    int tries_skipped_ = 0;
    int first_ = 0; // ladder index of the first step
    bool first_window_ = true;
};

} // namespace sph::parallel
