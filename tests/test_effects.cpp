// Effects the scene names (src/sph/effects/): the list is exactly the scene's,
// and each effect does what its paper says.
#include "scene/input_error.hpp"
#include "scene/scene_setup.hpp"
#include "sph/effects/surface_tension.hpp"
#include "sph/sources/emitter.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

using namespace sph;

namespace {

// A 4 cm square of 400 particles in the middle of a 10 cm box, no gravity.
Scene square_blob(const std::string& solver, const std::string& effects) {
    return default_scene({{"domain.max", "[0.1,0.1]"},
                          {"fluid.spacing", "0.002"},
                          {"fluid.blocks", R"([{"min":[0.03,0.03],"max":[0.07,0.07]}])"},
                          {"material.viscosity", "0.1"},
                          {"solver.name", solver},
                          {"effects", effects}});
}

// How far the outline is from a circle: the standard deviation of the
// outline's radius over its mean, the outline taken as the farthest particle
// from the centre in each of 16 sectors. 0.13 for this square, 0 for a circle.
Real irregularity(const State<2>& state) {
    Vec<2> centre(0);
    for (const auto& x : state.position)
        centre += x;
    centre /= Real(state.size());
    std::array<Real, 16> outline{};
    for (const auto& x : state.position) {
        const Vec<2> d = x - centre;
        const Real angle = std::atan2(d.y, d.x) + std::numbers::pi;
        const auto sector = std::size_t(angle / (2 * std::numbers::pi) * 16) % 16;
        outline[sector] = std::max(outline[sector], glm::length(d));
    }
    Real mean = 0, square_sum = 0;
    for (Real r : outline)
        mean += r / 16;
    for (Real r : outline)
        square_sum += (r - mean) * (r - mean) / 16;
    return std::sqrt(square_sum) / mean;
}

// A 20 cm box at spacing 4 mm, dfsph, with these blocks and effects.
Scene box_scene(const std::string& blocks, const std::string& effects) {
    return default_scene({{"domain.max", "[0.2,0.2]"},
                          {"fluid.spacing", "0.004"},
                          {"fluid.blocks", blocks},
                          {"solver.name", "dfsph"},
                          {"effects", effects}});
}

bool inside_domain(const Params<2>& p, const Vec<2>& x) {
    return x.x >= p.domain.min.x && x.x <= p.domain.max.x && x.y >= p.domain.min.y &&
           x.y <= p.domain.max.y;
}

const Emitter<2>& the_emitter(const Simulation<2>& sim) {
    for (const auto& e : sim.sources())
        if (e->name() == "emitters")
            return dynamic_cast<const Emitter<2>&>(*e);
    throw std::logic_error("no emitter");
}

std::vector<std::string> effect_names(const EffectList<2>& effects) {
    std::vector<std::string> names;
    for (const auto& e : effects)
        names.emplace_back(e->name());
    return names;
}

} // namespace

TEST_CASE("the step holds exactly the effects the scene lists", "[effects]") {
    using Names = std::vector<std::string>;
    // The default fluid is viscous (the seed's 1 Pa.s): see test_viscosity.cpp.
    CHECK(effect_names(make_effects<2>(default_scene({}))) == Names{"gravity", "viscosity"});
    const Override inviscid{"material.viscosity", "0"};
    CHECK(effect_names(make_effects<2>(default_scene({inviscid}))) == Names{"gravity"});
    CHECK(effect_names(make_effects<2>(default_scene({{"effects", "{}"}, inviscid}))).empty());
    CHECK(effect_names(make_effects<2>(
              default_scene({{"effects", R"({"surface_tension": {"gamma": 2}})"}, inviscid}))) ==
          Names{"surface_tension"});
    const auto both = make_effects<2>(
        default_scene({{"effects", R"({"gravity": [0, -1], "surface_tension": {}})"}, inviscid}));
    REQUIRE(effect_names(both) == Names{"gravity", "surface_tension"});
    // Defaults: gamma 1.
    CHECK(dynamic_cast<const SurfaceTension<2>&>(*both[1]).coefficient() == 1);
}

TEST_CASE("surface tension rounds a square blob in zero gravity", "[effects]") {
    for (const char* solver : {"wcsph", "dfsph"}) {
        INFO(solver);
        auto with = make_simulation<2>(square_blob(solver, R"({"surface_tension": {"gamma": 1}})"));
        auto without = make_simulation<2>(square_blob(solver, "{}"));
        REQUIRE(with.state().size() == 400);
        CHECK(irregularity(with.state()) == Approx(0.13).margin(0.005));
        with.advance_to(0.5);
        without.advance_to(0.5);
        // Round, up to the drop's own capillary oscillation (dfsph, less
        // damped, keeps a few percent of it at 0.5 s).
        CHECK(irregularity(with.state()) < 0.04);
        // Without it nothing pulls the corners in: wcsph clamps negative
        // pressure, dfsph does not pull.
        CHECK(irregularity(without.state()) > 0.12);
    }
}

TEST_CASE("surface tension forces are equal and opposite: momentum stays zero", "[effects]") {
    auto sim = make_simulation<2>(square_blob("wcsph", R"({"surface_tension": {"gamma": 1}})"));
    sim.advance_to(0.2);
    Vec<2> momentum(0);
    Real speeds = 0;
    for (const auto& v : sim.state().velocity) {
        momentum += v;
        speeds += glm::length(v);
    }
    REQUIRE(speeds > 0.01); // it moved
    CHECK(glm::length(momentum) < 1e-12 * speeds);
}

TEST_CASE("the cohesion spline attracts far and repels near, in 2D and 3D", "[effects]") {
    const CohesionSpline<2> c2(0.01);
    const CohesionSpline<3> c3(0.01);
    for (Real r : {0.001, 0.002}) {
        CHECK(c2(r) < 0);
        CHECK(c3(r) < 0);
    }
    for (Real r : {0.004, 0.006, 0.009}) {
        CHECK(c2(r) > 0);
        CHECK(c3(r) > 0);
    }
    CHECK(c2(0.011) == 0);
    // Continuous at h/2.
    CHECK(c3(0.005 - 1e-12) == Approx(c3(0.005 + 1e-12)).epsilon(1e-6));
    // 2D's constant gives the plane integral of the 3D one over space.
    Real i2 = 0, i3 = 0;
    const int steps = 20000;
    for (int k = 0; k < steps; ++k) {
        const Real r = (k + 0.5) * 0.01 / steps, dr = 0.01 / steps;
        i2 += c2(r) * 2 * std::numbers::pi * r * dr;
        i3 += c3(r) * 4 * std::numbers::pi * r * r * dr;
    }
    CHECK(i2 == Approx(i3).epsilon(1e-3));
}

TEST_CASE("an emitter adds particles at its rate, finite, with new ids", "[effects]") {
    // 10 particles a batch, every 4 mm / (1 m/s) = 4 ms: 2,500 particles/s
    // from 0.02 s to 0.3 s.
    const Scene scene = box_scene(R"([{"min":[0,0],"max":[0.2,0.008]}])",
                                  R"({"gravity": [0, -9.81], "emitters": [{"min": [0, 0.12],
             "max": [0.004, 0.16], "velocity": [1, 0], "start": 0.02, "end": 0.3}]})");
    auto sim = make_simulation<2>(scene);
    const std::size_t initial = sim.state().size();
    REQUIRE(initial == 100);
    const auto& emitter = the_emitter(sim);
    CHECK(emitter.batch() == 10);
    CHECK(emitter.rate() == Approx(2500));
    for (Real t : {0.01, 0.1, 0.2, 0.35}) {
        sim.advance_to(t);
        const Real expected = emitter.rate() * (std::min(t, 0.3) - std::min(t, 0.02));
        INFO("t = " << t);
        CHECK(std::abs(Real(sim.state().size() - initial) - expected) <= emitter.batch());
    }
    // Every particle finite, inside, with its own id.
    std::vector<std::uint32_t> ids = sim.state().id;
    std::sort(ids.begin(), ids.end());
    for (std::size_t i = 0; i < ids.size(); ++i)
        CHECK(ids[i] == i);
    for (std::size_t i = 0; i < sim.state().size(); ++i) {
        CHECK(std::isfinite(sim.state().velocity[i].x + sim.state().velocity[i].y));
        CHECK(std::isfinite(sim.state().density[i]));
        CHECK(inside_domain(sim.params(), sim.state().position[i]));
    }
}

TEST_CASE("emitters are checked when read", "[effects]") {
    auto bad = [](const char* emitter) {
        try {
            default_scene({{"effects", std::string(R"({"emitters": [)") + emitter + "]}"}});
        } catch (const InputError& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(bad(R"({"min": [0, 0], "max": [0.01, 0.01], "velocity": [0, 0]})")
              .find("effects.emitters[0].velocity") != std::string::npos);
    CHECK(bad(R"({"min": [0, 0], "max": [0.01, 0.01], "velocity": [1, 0], "start": 1, "end": 0.5})")
              .find("effects.emitters[0].end") != std::string::npos);
    // Thinner than a spacing (the built-in scene's 1.4 mm): no particle, no
    // stream (it would emit empty batches forever).
    CHECK(bad(R"({"min": [0.1, 0.1], "max": [0.101, 0.11], "velocity": [1, 0]})")
              .find("the emitter's box is thinner than one spacing") != std::string::npos);
    CHECK(bad(R"({"min": [0.1, 0.1], "max": [0.5, 0.11], "velocity": [1, 0]})")
              .find("outside the domain") != std::string::npos);
}

TEST_CASE("a flooded emitter waits instead of stacking particles", "[effects]") {
    // The inlet sits inside a block of fluid at rest, no gravity: nothing
    // leaves its box, so nothing may be emitted.
    const Scene scene = box_scene(R"([{"min":[0,0],"max":[0.2,0.2]}])",
                                  R"({"emitters": [{"min": [0.1, 0.1], "max": [0.104, 0.14],
             "velocity": [1, 0]}]})");
    auto sim = make_simulation<2>(scene);
    const std::size_t initial = sim.state().size();
    sim.advance_to(0.02);
    // Its rate would give 50 particles by now; it pushes the water ahead (its
    // inlet zone moves at 1 m/s) and emits only into the room that makes.
    const auto& emitter = the_emitter(sim);
    CHECK(sim.state().size() - initial <= 20);
    CHECK(emitter.blocked_seconds() > 0.01);
    // Nothing landed on anything.
    Real closest = 1;
    const auto& x = sim.state().position;
    for (std::size_t i = 0; i < x.size(); ++i)
        for (std::size_t j = i + 1; j < x.size(); ++j)
            closest = std::min(closest, glm::length(x[i] - x[j]));
    CHECK(closest > 0.3 * 0.004);
}

TEST_CASE("an effect the scene does not name allocates nothing", "[effects]") {
    auto bytes_of_effects = [](const Simulation<2>& sim) {
        std::size_t total = 0;
        for (const auto& e : sim.effects())
            total += e->bytes();
        return total;
    };
    // Gravity and viscosity keep no arrays; surface tension keeps its normals.
    auto plain = make_simulation<2>(square_blob("wcsph", R"({"gravity": [0, -9.81]})"));
    auto tension = make_simulation<2>(square_blob("wcsph", R"({"surface_tension": {}})"));
    plain.step();
    tension.step();
    CHECK(bytes_of_effects(plain) == 0);
    CHECK(bytes_of_effects(tension) >= tension.state().size() * sizeof(Vec<2>));
    // The particles' own arrays are the same whatever the effects.
    std::size_t arrays_plain = 0, arrays_tension = 0;
    plain.state().for_each_array([&](auto&) { ++arrays_plain; });
    tension.state().for_each_array([&](auto&) { ++arrays_tension; });
    CHECK(arrays_plain == arrays_tension);
    // No walls made of particles and no obstacles: no boundary set at all.
    auto seed = make_simulation<2>(default_scene({{"fluid.spacing", "0.005715"}}));
    CHECK(seed.boundary() == nullptr);
}

TEST_CASE("a disc emitter emits only within its radius of the axis", "[effects]") {
    // A 3D inlet box 4 cm x 4 cm across, one spacing (4 mm) thick along x,
    // cut to a disc of radius 1.5 cm: 10 x 10 sites, of which those within
    // 1.5 cm of the axis.
    auto scene = [](const std::string& radius) {
        return default_scene(
            {{"dimension", "3"},
             {"domain.max", "[0.2,0.2,0.2]"},
             {"fluid.spacing", "0.004"},
             {"fluid.blocks", R"([{"min":[0,0,0],"max":[0.2,0.008,0.2]}])"},
             {"solver.name", "dfsph"},
             {"effects", R"({"emitters": [{"min": [0, 0.08, 0.08], "max": [0.004, 0.12, 0.12],
                             "velocity": [1, 0, 0])" +
                             radius + "}]}"}});
    };
    auto sim = make_simulation<3>(scene(R"(, "radius": 0.015)"));
    const auto& emitter = [&]() -> const Emitter<3>& {
        for (const auto& e : sim.sources())
            if (e->name() == "emitters")
                return dynamic_cast<const Emitter<3>&>(*e);
        throw std::logic_error("no emitter");
    }();
    std::size_t expected = 0;
    for (int j = 0; j < 10; ++j)
        for (int k = 0; k < 10; ++k) {
            const double y = (j + 0.5) * 0.004 - 0.02, z = (k + 0.5) * 0.004 - 0.02;
            expected += std::sqrt(y * y + z * z) <= 0.015;
        }
    CHECK(emitter.batch() == expected);
    CHECK(expected < 100);
    const std::size_t initial = sim.state().size();
    sim.advance_to(0.001); // the first batch, just out of the box
    REQUIRE(sim.state().size() == initial + expected);
    for (std::size_t i = initial; i < sim.state().size(); ++i) {
        const auto& x = sim.state().position[i];
        CHECK(std::hypot(x.y - 0.1, x.z - 0.1) <= 0.015 + 1e-9);
    }
    // A radius that holds no site is an error naming the field.
    try {
        make_simulation<3>(scene(R"(, "radius": 0.001)"));
        FAIL("accepted");
    } catch (const InputError& e) {
        CHECK_THAT(e.what(), Catch::Contains("effects.emitters[0].radius"));
    }
}
