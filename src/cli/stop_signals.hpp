#pragma once
// SIGINT, SIGTERM, SIGHUP (a closed terminal, a dropped ssh), SIGQUIT and
// SIGPIPE (an output pipe closed) ask the program to stop, not kill it:
// `sphclip run` finishes its outputs and exits 130, and `study` and
// `validate` ask their child runs to stop and report what ran
// (docs/contract.md, "Signals"). main() installs the guard before anything
// else, so a signal during start-up is not lost either. SIGXFSZ is ignored
// meanwhile: a file past `ulimit -f` is then a write error (EFBIG), reported
// like a full disk.

#include <csignal>
#include <iterator>

namespace sph {

// Installs the stop handler for those signals while it lives and puts the
// earlier handlers back after. Guards may nest (a run inside a command):
// the request recorded is the process's, kept from the first signal on.
class StopSignals {
  public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;

    // The signal that asked to stop since the guard was made; 0 when none.
    static int received();

    // The signals that ask to stop.
    static constexpr int signals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGPIPE};

  private:
    struct sigaction previous_[std::size(signals)]{};
    struct sigaction previous_file_size_ {}; // SIGXFSZ's, ignored while the guard lives
};

} // namespace sph
