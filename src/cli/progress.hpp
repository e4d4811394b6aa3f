#pragma once
// The progress of long runs: frame k/N, simulated time, steps/s, ETA.
// On a terminal a line redrawn in place, at most a few times a second; in a
// log (CI, nohup, a batch job) a plain line every `interval` seconds of wall
// time and one when the run ends, so a log shows the run is alive and how far
// it got (`--progress`, README "Command line").

#include <cstdint>
#include <optional>
#include <string>

namespace sph {

enum class ProgressMode { bar, lines, none };

// `--progress auto|bar|lines|none` and --quiet as one mode: auto is the bar
// when standard output is a terminal, else lines; --quiet turns auto into
// none but keeps a --progress bar or lines asked for by name.
ProgressMode progress_mode(const std::string& choice, bool quiet, bool terminal);

// Seconds of wall time between two plain lines: 10, or the
// SPHCLIP_PROGRESS_INTERVAL_S environment variable (a number >= 0, for
// tests; 0 prints a line per frame). Throws InputError for a bad value.
double progress_interval();

class Progress {
  public:
    Progress(ProgressMode mode, double interval_seconds)
        : mode_(mode), interval_(interval_seconds) {}
    // After frame `frame` (0-based) of `frames`, at simulated `time`, after
    // `steps` steps and `wall_seconds` since the run started.
    void update(std::uint64_t frame, std::uint64_t frames, double time, std::uint64_t steps,
                double wall_seconds);
    // The run ended: the bar's line is ended, so later output starts on a
    // fresh one; in lines mode the last frame reached is told once more.
    void done(double wall_seconds);

  private:
    struct Reading {
        std::uint64_t frame = 0, frames = 0, steps = 0;
        double time = 0, wall = 0;
    };
    std::string describe(const Reading& r) const;

    ProgressMode mode_;
    double interval_;
    bool drawn_ = false;
    double last_drawn_ = 0; // wall seconds when the bar or the last line was drawn
    std::optional<Reading> last_;
};

} // namespace sph
