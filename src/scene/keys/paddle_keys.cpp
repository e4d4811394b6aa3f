// effects.paddles: the keys are declared in sph/boundaries/paddle_keys.cpp; here each paddle is
// checked against the scene.
#include "scene/keys/scene_keys.hpp"

namespace sph {

double check_paddle(const FieldReader& r, const Scene& s, std::size_t i, double layers) {
    const ScenePaddle& o = s.effects.paddles[i];
    const int dim = s.dimension;
    const std::string p = fmt::format("effects.paddles[{}]", i);
    const bool sine = o.motion == PaddleMotion::sine;
    // How far the motion takes the box from rest over the clip, per axis.
    const double moving = std::max(0.0, std::min(o.end, s.duration) - o.start);
    double sites = 1, interior = 1;
    for (int a = 0; a < dim; ++a) {
        if (!(o.min[a] < o.max[a]))
            r.fail(p, fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                  "xyz"[a], o.min[a], o.max[a]));
        const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
        auto outside = [&](double lo, double hi) {
            return lo < s.domain.min[a] - tolerance || hi > s.domain.max[a] + tolerance;
        };
        if (outside(o.min[a], o.max[a]))
            r.fail(p, fmt::format("the paddle's box [{}, {}] on axis {} is outside the domain "
                                  "[{}, {}]",
                                  o.min[a], o.max[a], "xyz"[a], s.domain.min[a], s.domain.max[a]));
        const double travel = sine ? 0 : o.velocity[a] * moving;
        const double back = sine ? std::abs(o.amplitude[a]) : std::max(0.0, -travel);
        const double forth = sine ? std::abs(o.amplitude[a]) : std::max(0.0, travel);
        if (outside(o.min[a] - back, o.max[a] + forth))
            r.fail(p + (sine ? ".amplitude" : ".velocity"),
                   fmt::format("moves the paddle outside the domain on axis {}: over the clip "
                               "it spans [{:.6g}, {:.6g}], against [{}, {}]",
                               "xyz"[a], o.min[a] - back, o.max[a] + forth, s.domain.min[a],
                               s.domain.max[a]));
        const double along = (o.max[a] - o.min[a]) / s.fluid.spacing;
        if (!(along >= 1 - 1e-9))
            r.fail(p, fmt::format("the paddle is thinner than one spacing ({} m) on axis {}: too "
                                  "thin a solid for the fluid to see",
                                  s.fluid.spacing, "xyz"[a]));
        sites *= std::max(1.0, std::round(along));
        interior *= std::max(0.0, std::round(along) - 2 * layers);
    }
    return sites - interior;
}

} // namespace sph
