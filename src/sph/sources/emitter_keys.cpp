#include "sph/sources/emitter_keys.hpp"

namespace sph {

namespace {

std::optional<KeyProblem> check_emitter(const SceneEmitter& e, int dimension) {
    double speed = 0;
    for (int a = 0; a < dimension; ++a)
        speed += e.velocity[a] * e.velocity[a];
    if (!(speed > 0))
        return KeyProblem{"velocity", "an emitter needs a velocity that is not zero"};
    if (!(e.start < e.end))
        return KeyProblem{"end", "must be after start"};
    return std::nullopt;
}

} // namespace

const KeyList<SceneEmitter>& emitter_keys() {
    using S = SceneEmitter;
    // (A table of its own: GCC 12 fails on it nested in the list's aggregate.)
    static const KeyTable<S> element{
        {.path = "min", .field = &S::min, .unit = "m", .doc = "Lower corner of the emitter's box."},
        {.path = "max", .field = &S::max, .unit = "m", .doc = "Upper corner of the emitter's box."},
        {.path = "velocity",
         .field = &S::velocity,
         .unit = "m/s",
         .doc = "Velocity of the emitted particles (not zero)."},
        {.path = "start",
         .field = &S::start,
         .unit = "s",
         .doc = "When the emitter starts.",
         .bound = Bound::non_negative},
        {.path = "end",
         .field = &S::end,
         .unit = "s",
         .doc = "When the emitter stops.",
         .bound = Bound::non_negative},
        {.path = "radius",
         .field = &S::radius,
         .unit = "m",
         .doc = "A disc inlet (a round pipe in 3D): only the box's lattice sites within "
                "this distance of the axis through its centre along velocity are "
                "emitted.",
         .bound = Bound::positive,
         .absent = "the whole box"}};
    static const KeyList<S> keys{
        .path = "effects.emitters",
        .doc = "Streams of fluid entering the domain: each box is filled on the fluid's lattice "
               "and emitted whole every (its thickness along velocity) / |velocity| seconds.",
        .keys = element,
        .check = check_emitter,
    };
    return keys;
}

} // namespace sph
