#include "cli/stop_signals.hpp"

namespace sph {

namespace {

// A handler may only store to a lock-free flag.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void record_stop(int signal) {
    // The first request is the one reported.
    if (stop_signal == 0)
        stop_signal = signal;
}

} // namespace

StopSignals::StopSignals() {
    struct sigaction action {};
    action.sa_handler = record_stop;
    sigemptyset(&action.sa_mask);
    // Interrupted system calls resume: a write to a frame or to the video in
    // progress completes, and the loops look at received() between steps.
    action.sa_flags = SA_RESTART;
    for (std::size_t k = 0; k < std::size(signals); ++k)
        sigaction(signals[k], &action, &previous_[k]);
    // SIGXFSZ ignored: a write past the file-size limit (`ulimit -f`) then
    // fails with EFBIG, which the run reports as a full disk and survives
    // (docs/contract.md), instead of the process being killed with a core.
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGXFSZ, &ignore, &previous_file_size_);
}

StopSignals::~StopSignals() {
    for (std::size_t k = 0; k < std::size(signals); ++k)
        sigaction(signals[k], &previous_[k], nullptr);
    sigaction(SIGXFSZ, &previous_file_size_, nullptr);
}

int StopSignals::received() {
    return stop_signal;
}

} // namespace sph
