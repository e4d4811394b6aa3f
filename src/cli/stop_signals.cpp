#include "cli/stop_signals.hpp"

namespace sph {

namespace {

// A handler may only store to a lock-free flag.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void record_stop(int signal) {
    stop_signal = signal;
}

} // namespace

StopSignals::StopSignals() {
    stop_signal = 0;
    struct sigaction action {};
    action.sa_handler = record_stop;
    sigemptyset(&action.sa_mask);
    // Interrupted system calls resume: a write to a frame or to the video in
    // progress completes, and the loops look at received() between steps.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, &previous_int_);
    sigaction(SIGTERM, &action, &previous_term_);
}

StopSignals::~StopSignals() {
    sigaction(SIGINT, &previous_int_, nullptr);
    sigaction(SIGTERM, &previous_term_, nullptr);
}

int StopSignals::received() {
    return stop_signal;
}

} // namespace sph
