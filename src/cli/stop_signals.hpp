#pragma once
// SIGINT and SIGTERM ask the program to stop, not kill it: `sphclip run`
// finishes its outputs and exits 130, and `study` and `validate` ask their
// child runs to stop and report what ran (README, "Exit codes").

#include <csignal>

namespace sph {

// Installs the stop handler for SIGINT and SIGTERM while it lives and puts
// the earlier handlers back after. One at a time: the request it records is
// the process's.
class StopSignals {
  public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

    // The signal that asked to stop since the guard was made; 0 when none.
    static int received();

  private:
    struct sigaction previous_int_ {};
    struct sigaction previous_term_ {};
};

} // namespace sph
