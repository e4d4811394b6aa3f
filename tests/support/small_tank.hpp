#pragma once
// The command-line tests' scene: a small 2D tank, 36 particles in the corner
// of a 0.1 m box, at 40 frames a second, so that a run takes well under a
// second.

#include <fmt/format.h>
#include <string>

namespace sph::test {

// `duration` s of it: 0.05 s is 3 frames, 0.1 s is 5.
inline std::string small_tank(double duration) {
    return fmt::format(R"({{
    "domain": {{"min": [0, 0], "max": [0.1, 0.1]}},
    "fluid": {{"spacing": 0.005, "blocks": [{{"min": [0, 0], "max": [0.03, 0.03]}}]}},
    "duration": {}, "fps": 40
}})",
                       duration);
}

} // namespace sph::test
