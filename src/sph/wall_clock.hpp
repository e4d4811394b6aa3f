#pragma once
// The one clock every timing in sphclip reads (stage table, frame and
// encoder timings): monotonic, so a clock change during a run cannot give a
// negative or inflated time.

#include <chrono>

namespace sph {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace sph
