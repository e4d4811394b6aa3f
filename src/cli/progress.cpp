#include "cli/progress.hpp"

#include "cli/console.hpp"
#include "scene/input_error.hpp"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>

namespace sph {

ProgressMode progress_mode(const std::string& choice, bool quiet, bool terminal) {
    if (choice == "bar")
        return ProgressMode::bar;
    if (choice == "lines")
        return ProgressMode::lines;
    if (choice == "none" || quiet)
        return ProgressMode::none;
    return terminal ? ProgressMode::bar : ProgressMode::lines;
}

double progress_interval() {
    const char* text = std::getenv("SPHCLIP_PROGRESS_INTERVAL_S");
    if (text == nullptr || *text == '\0')
        return 10;
    char* end = nullptr;
    const double seconds = std::strtod(text, &end);
    if (*end != '\0' || !std::isfinite(seconds) || seconds < 0)
        throw InputError("environment", "SPHCLIP_PROGRESS_INTERVAL_S",
                         fmt::format("expected seconds (a number >= 0), got '{}'", text));
    return seconds;
}

std::string Progress::describe(const Reading& r) const {
    const double rate = r.wall > 0 ? double(r.steps) / r.wall : 0;
    // Frames so far at their mean wall time each; frame 0 is the initial state.
    const double eta = r.frame > 0 ? r.wall / double(r.frame) * double(r.frames - 1 - r.frame) : 0;
    return fmt::format("frame {}/{}  t = {:.3f} s  {:.0f} steps/s  ETA {:.0f} s", r.frame + 1,
                       r.frames, r.time, rate, eta);
}

void Progress::update(std::uint64_t frame, std::uint64_t frames, double time, std::uint64_t steps,
                      double wall_seconds) {
    if (mode_ == ProgressMode::none)
        return;
    last_ = Reading{frame, frames, steps, time, wall_seconds};
    if (mode_ == ProgressMode::bar) {
        if (drawn_ && wall_seconds - last_drawn_ < 0.2 && frame + 1 < frames)
            return;
        say("\r{}   ", describe(*last_));
    } else {
        // The last frame's line is done()'s.
        if (wall_seconds - last_drawn_ < interval_ || frame + 1 >= frames)
            return;
        say("sphclip: {}\n", describe(*last_));
    }
    last_drawn_ = wall_seconds;
    drawn_ = true;
}

void Progress::done(double wall_seconds) {
    if (mode_ == ProgressMode::bar && drawn_)
        say("\n");
    if (mode_ == ProgressMode::lines && last_)
        say("sphclip: frame {}/{}  t = {:.3f} s  {:.0f} steps/s  ended after {:.1f} s\n",
            last_->frame + 1, last_->frames, last_->time,
            last_->wall > 0 ? double(last_->steps) / last_->wall : 0.0, wall_seconds);
    drawn_ = false;
}

} // namespace sph
