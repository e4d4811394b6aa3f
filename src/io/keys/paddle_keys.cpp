// The effects.paddles family's keys, read, checked and written by hand: a list of boxes, each with
// the keys of its motion. (Their declarations move next to the family once it has its own folder.)
#include "io/keys/scene_keys.hpp"

namespace sph {

void read_paddles(FieldReader& r, int dim, std::vector<ScenePaddle>& paddles) {
    const std::size_t count = r.list(
        "effects.paddles", "none",
        "Boxes that move with a prescribed motion (wcsph, dfsph), a piston wavemaker: made of "
        "boundary particles that push the fluid and drag it along (no slip).");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.paddles[{}]", i);
        const ScenePaddle fallback;
        ScenePaddle o;
        o.min = r.vector(p + ".min", fallback.min, dim, "m",
                         "Lower corner of the paddle's box at rest (before start).");
        o.max = r.vector(p + ".max", fallback.max, dim, "m",
                         "Upper corner of the paddle's box at rest.");
        o.motion = r.choice(p + ".motion", fallback.motion, {"sine", "linear"},
                            "How the paddle moves from start on: sine, displacement amplitude "
                            "sin(2 pi (t - start) / period); linear, velocity (t - start) until "
                            "end, then it stays.");
        o.amplitude = r.vector(p + ".amplitude", fallback.amplitude, dim, "m",
                               "Sine: the largest displacement (half the stroke), as a vector "
                               "along the motion.");
        o.period =
            r.number(p + ".period", fallback.period, "s", "Sine: the period.", Bound::positive);
        o.velocity = r.vector(p + ".velocity", fallback.velocity, dim, "m/s",
                              "Linear: the velocity (not zero).");
        o.start = r.number(p + ".start", fallback.start, "s", "When the paddle starts moving.",
                           Bound::non_negative);
        o.end = r.number(p + ".end", fallback.end, "s", "Linear: when the paddle stops.",
                         Bound::non_negative);
        if (i >= count)
            break;
        // Keys of the other motion would be silently ignored: refused instead.
        const bool sine = o.motion == "sine";
        for (const char* key : {".velocity", ".end"})
            if (sine && r.present(p + key))
                r.fail(p + key, "is for motion \"linear\"; a sine paddle has amplitude and period");
        for (const char* key : {".amplitude", ".period"})
            if (!sine && r.present(p + key))
                r.fail(p + key, "is for motion \"sine\"; a linear paddle has velocity and end");
        if (!sine) {
            double speed = 0;
            for (int a = 0; a < dim; ++a)
                speed += o.velocity[a] * o.velocity[a];
            if (!(speed > 0))
                r.fail(p + ".velocity", "a linear paddle needs a velocity that is not zero");
            if (!(o.start < o.end))
                r.fail(p + ".end", "must be after start");
        }
        paddles.push_back(o);
    }
}

json write_paddles(const std::vector<ScenePaddle>& paddles, int dim) {
    auto vec = [dim](const Vec3& v) {
        return std::vector<double>(v.begin(), v.begin() + dim);
    };
    json out = json::array();
    for (const auto& o : paddles) {
        json paddle = {{"min", vec(o.min)}, {"max", vec(o.max)}, {"motion", o.motion}};
        if (o.motion == "sine") {
            paddle["amplitude"] = vec(o.amplitude);
            paddle["period"] = o.period;
        } else {
            paddle["velocity"] = vec(o.velocity);
            paddle["end"] = o.end;
        }
        paddle["start"] = o.start;
        out.push_back(paddle);
    }
    return out;
}

double check_paddle(const FieldReader& r, const Scene& s, std::size_t i, double layers) {
    const ScenePaddle& o = s.effects.paddles[i];
    const int dim = s.dimension;
    const std::string p = fmt::format("effects.paddles[{}]", i);
    const bool sine = o.motion == "sine";
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
