// The effects.emitters family's keys, read, checked and written by hand: a list of boxes with a
// time window. (Their declarations move next to the family once it has its own folder.)
#include "io/keys/scene_keys.hpp"

namespace sph {

void read_emitters(FieldReader& r, int dim, std::vector<SceneEmitter>& emitters) {
    const std::size_t count = r.list(
        "effects.emitters", "none",
        "Streams of fluid entering the domain: each box is filled on the fluid's lattice and "
        "emitted whole every (its thickness along velocity) / |velocity| seconds.");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.emitters[{}]", i);
        const SceneEmitter fallback;
        SceneEmitter e;
        e.min = r.vector(p + ".min", fallback.min, dim, "m", "Lower corner of the emitter's box.");
        e.max = r.vector(p + ".max", fallback.max, dim, "m", "Upper corner of the emitter's box.");
        e.velocity = r.vector(p + ".velocity", fallback.velocity, dim, "m/s",
                              "Velocity of the emitted particles (not zero).");
        e.start = r.number(p + ".start", fallback.start, "s", "When the emitter starts.",
                           Bound::non_negative);
        e.end =
            r.number(p + ".end", fallback.end, "s", "When the emitter stops.", Bound::non_negative);
        e.radius = r.optional_number(
            p + ".radius", "m", "the whole box",
            "A disc inlet (a round pipe in 3D): only the box's lattice sites within this "
            "distance of the axis through its centre along velocity are emitted.",
            Bound::positive);
        if (i >= count)
            break;
        double speed = 0;
        for (int a = 0; a < dim; ++a)
            speed += e.velocity[a] * e.velocity[a];
        if (!(speed > 0))
            r.fail(p + ".velocity", "an emitter needs a velocity that is not zero");
        if (!(e.start < e.end))
            r.fail(p + ".end", "must be after start");
        emitters.push_back(e);
    }
}

json write_emitters(const std::vector<SceneEmitter>& emitters, int dim) {
    auto vec = [dim](const Vec3& v) {
        return std::vector<double>(v.begin(), v.begin() + dim);
    };
    json out = json::array();
    for (const auto& e : emitters) {
        json emitter = {{"min", vec(e.min)},
                        {"max", vec(e.max)},
                        {"velocity", vec(e.velocity)},
                        {"start", e.start},
                        {"end", e.end}};
        if (e.radius)
            emitter["radius"] = *e.radius;
        out.push_back(emitter);
    }
    return out;
}
} // namespace sph
