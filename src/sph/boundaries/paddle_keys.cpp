#include "sph/boundaries/paddle_keys.hpp"

namespace sph {

namespace {

bool sine(const ScenePaddle& p) {
    return p.motion == PaddleMotion::sine;
}
bool linear(const ScenePaddle& p) {
    return !sine(p);
}

std::optional<KeyProblem> check_paddle_motion(const ScenePaddle& p, int dimension) {
    if (sine(p))
        return std::nullopt;
    double speed = 0;
    for (int a = 0; a < dimension; ++a)
        speed += p.velocity[a] * p.velocity[a];
    if (!(speed > 0))
        return KeyProblem{"velocity", "a linear paddle needs a velocity that is not zero"};
    if (!(p.start < p.end))
        return KeyProblem{"end", "must be after start"};
    return std::nullopt;
}

} // namespace

const KeyList<ScenePaddle>& paddle_keys() {
    using S = ScenePaddle;
    // Keys of the other motion would be silently ignored: refused instead.
    const std::string for_sine = "is for motion \"sine\"; a linear paddle has velocity and end";
    const std::string for_linear =
        "is for motion \"linear\"; a sine paddle has amplitude and period";
    // (A table of its own: GCC 12 fails on a list of strings in a nested aggregate.)
    static const KeyTable<S> element{
        {.path = "min",
         .field = &S::min,
         .unit = "m",
         .doc = "Lower corner of the paddle's box at rest (before start)."},
        {.path = "max",
         .field = &S::max,
         .unit = "m",
         .doc = "Upper corner of the paddle's box at rest."},
        {.path = "motion",
         .field = enum_field<&S::motion>(),
         .doc = "How the paddle moves from start on: sine, displacement amplitude "
                "sin(2 pi (t - start) / period); linear, velocity (t - start) until "
                "end, then it stays.",
         .choices = {"sine", "linear"}},
        {.path = "amplitude",
         .field = &S::amplitude,
         .unit = "m",
         .doc = "Sine: the largest displacement (half the stroke), as a vector along "
                "the motion.",
         .applies = sine,
         .refused = for_sine},
        {.path = "period",
         .field = &S::period,
         .unit = "s",
         .doc = "Sine: the period.",
         .bound = Bound::positive,
         .applies = sine,
         .refused = for_sine},
        {.path = "velocity",
         .field = &S::velocity,
         .unit = "m/s",
         .doc = "Linear: the velocity (not zero).",
         .applies = linear,
         .refused = for_linear},
        {.path = "start",
         .field = &S::start,
         .unit = "s",
         .doc = "When the paddle starts moving.",
         .bound = Bound::non_negative},
        {.path = "end",
         .field = &S::end,
         .unit = "s",
         .doc = "Linear: when the paddle stops.",
         .bound = Bound::non_negative,
         .applies = linear,
         .refused = for_linear}};
    static const KeyList<S> keys{
        .path = "effects.paddles",
        .doc = "Boxes that move with a prescribed motion (wcsph, dfsph), a piston wavemaker: "
               "made of boundary particles that push the fluid and drag it along (no slip).",
        .keys = element,
        .check = check_paddle_motion,
    };
    return keys;
}

} // namespace sph
