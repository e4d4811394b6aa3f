#pragma once
// The progress line of long runs: frame k/N, simulated time, steps/s, ETA.
// Drawn only on a terminal, at most a few times a second.

#include <chrono>
#include <cstdint>
#include <cstdio>

namespace sph {

class Progress {
  public:
    explicit Progress(bool enabled) : enabled_(enabled) {}
    void update(std::uint64_t frame, std::uint64_t frames, double time, std::uint64_t steps,
                double wall_seconds);
    // Ends the line so later output starts on a fresh one.
    void done();

  private:
    bool enabled_;
    bool drawn_ = false;
    std::chrono::steady_clock::time_point last_{};
};

} // namespace sph
