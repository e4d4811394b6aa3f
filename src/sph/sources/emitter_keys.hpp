#pragma once
// The scene's `effects.emitters`: streams of fluid entering through a box
// (emitter.hpp emits them), and their keys.

#include "sph/scene_key.hpp"

#include <optional>

namespace sph {

// The box is filled on the fluid's lattice and emitted whole every
// thickness / |v| seconds between start and end.
struct SceneEmitter {
    Vec3 min{0, 0, 0}, max{0, 0, 0}; // m
    Vec3 velocity{0, 0, 0};          // m/s, not zero
    double start = 0;                // s
    double end = 1e300;              // s
    // m: a disc inlet, the box's sites within this distance of the axis
    // through its centre along the velocity; none: the whole box.
    std::optional<double> radius;
};

// effects.emitters: a list of boxes with a velocity and a time window.
const KeyList<SceneEmitter>& emitter_keys();

} // namespace sph
