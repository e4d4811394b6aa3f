#include "cli/progress.hpp"

#include "cli/console.hpp"

#include <fmt/format.h>

namespace sph {

void Progress::update(std::uint64_t frame, std::uint64_t frames, double time, std::uint64_t steps,
                      double wall_seconds) {
    if (!enabled_)
        return;
    const auto now = std::chrono::steady_clock::now();
    if (drawn_ && now - last_ < std::chrono::milliseconds(200) && frame + 1 < frames)
        return;
    last_ = now;
    drawn_ = true;
    const double rate = wall_seconds > 0 ? double(steps) / wall_seconds : 0;
    const double eta = frame > 0 ? wall_seconds / double(frame) * double(frames - 1 - frame) : 0;
    say("\rframe {}/{}  t = {:.3f} s  {:.0f} steps/s  ETA {:.0f} s   ", frame + 1, frames, time,
        rate, eta);
}

void Progress::done() {
    if (enabled_ && drawn_)
        say("\n");
    drawn_ = false;
}

} // namespace sph
