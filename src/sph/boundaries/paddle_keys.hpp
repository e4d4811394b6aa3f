#pragma once
// The scene's `effects.paddles`: boxes that move with a prescribed motion, a
// piston wavemaker (paddles.hpp moves them), and their keys.

#include "sph/boundaries/paddles.hpp"
#include "sph/scene_key.hpp"

#include <string>

namespace sph {

// Before `start` and at zero displacement the paddle is at [min, max].
struct ScenePaddle {
    Vec3 min{0, 0, 0}, max{0, 0, 0}; // m, the box at rest
    PaddleMotion motion = PaddleMotion::sine;
    Vec3 amplitude{0, 0, 0}; // m, sine: d = A sin(2 pi (t - start) / period)
    double period = 1;       // s, sine
    Vec3 velocity{0, 0, 0};  // m/s, linear: d = V (t - start) until end
    double start = 0;        // s
    double end = 1e300;      // s, linear
};

// effects.paddles: a list of boxes, each with the keys of its motion.
const KeyList<ScenePaddle>& paddle_keys();

} // namespace sph
