// Paddles (src/sph/boundaries/paddles.cpp and the scene's effects.paddles): boxes that
// move with a prescribed motion. Their boundary particles follow the motion,
// fluid in front of a piston is pushed along at its speed and never ends up
// inside it, the momentum it gets has the sign of the motion, a paddle the
// fluid never reaches leaves the fluid bit for bit as it is without it, the
// time step and the watchdog count the paddle's speed, and bad input is
// refused with its field named.
#include "scene/input_error.hpp"
#include "scene/scene.hpp"
#include "scene/scene_setup.hpp"
#include "sph/boundaries/paddles.hpp"
#include "sph/snapshot.hpp"
#include "sph/state_hash.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

using namespace sph;
using nlohmann::json;

namespace {

// A 2D channel, no gravity, a piston at its left end with water in front.
json piston_channel(const std::string& solver) {
    json scene = json::parse(R"({
        "duration": 0.3,
        "domain": {"min": [0, 0], "max": [0.6, 0.2]},
        "fluid": {"spacing": 0.005, "blocks": [{"min": [0.08, 0], "max": [0.3, 0.1]}]},
        "material": {"viscosity": 0.001},
        "effects": {"paddles": [{"min": [0.06, 0], "max": [0.08, 0.2], "motion": "linear",
                                 "velocity": [0.2, 0]}]}
    })");
    scene["solver"]["name"] = solver;
    return scene;
}

Scene parse(const json& scene) {
    return parse_scene(scene.dump(), "test.json", {});
}

std::optional<InputError> error_of(const json& scene) {
    try {
        parse(scene);
    } catch (const InputError& e) {
        return e;
    }
    return std::nullopt;
}

json with(json scene, const std::string& pointer, const json& value) {
    scene[json::json_pointer(pointer)] = value;
    return scene;
}

// Particles strictly inside the paddle's box at the simulation's time.
template <int D>
std::size_t inside_paddles(const Simulation<D>& sim) {
    std::size_t inside = 0;
    for (const Paddle<D>& p : sim.params().paddles) {
        const Box<D> box = p.box_at(sim.time());
        for (const Vec<D>& x : sim.state().position)
            inside += box.contains(x);
    }
    return inside;
}

} // namespace

TEST_CASE("a paddle's particles are where its motion has them", "[paddle]") {
    Paddle<2> sine;
    sine.box = {{0.1, 0}, {0.12, 0.2}};
    sine.amplitude = {0.03, 0.01};
    sine.period = 0.8;
    sine.start = 0.1;
    Paddle<2> linear;
    linear.box = {{0.4, 0}, {0.42, 0.1}};
    linear.motion = PaddleMotion::linear;
    linear.velocity = {-0.5, 0};
    linear.start = 0.05;
    linear.end = 0.25;
    const std::vector<Paddle<2>> paddles{sine, linear};
    const Real spacing = 0.005, h = 2.5 * spacing;
    PaddleSamples<2> samples = sample_paddles<2>(paddles, spacing, h, spacing * spacing);
    REQUIRE(samples.positions.size() == 4 * 40 + 4 * 20);
    const std::vector<Vec<2>> rest = samples.positions;
    const std::vector<std::uint32_t> owner = samples.paddle;
    BoundaryParticles<2> boundary(std::vector<Vec<2>>{}, std::vector<Real>{}, h);
    boundary.add_moving(std::move(samples.positions), std::move(samples.volumes),
                        std::move(samples.paddle));
    REQUIRE(boundary.moving_begin() == 0);
    const Real omega = 2 * std::numbers::pi_v<Real> / 0.8;
    for (const Real t : {0.0, 0.1, 0.2, 0.3, 0.5, 0.9}) {
        move_paddles<2>(paddles, t, boundary);
        const Vec<2> d_sine = t > 0.1 ? std::sin(omega * (t - 0.1)) * sine.amplitude : Vec<2>(0);
        const Vec<2> v_sine =
            t >= 0.1 ? omega * std::cos(omega * (t - 0.1)) * sine.amplitude : Vec<2>(0);
        const Vec<2> d_linear = (std::clamp(t, 0.05, 0.25) - 0.05) * linear.velocity;
        const Vec<2> v_linear = t >= 0.05 && t < 0.25 ? linear.velocity : Vec<2>(0);
        for (std::size_t k = 0; k < rest.size(); ++k) {
            const std::uint32_t b = static_cast<std::uint32_t>(k);
            const Vec<2> expected = rest[k] + (owner[k] == 0 ? d_sine : d_linear);
            CHECK(glm::length(boundary.positions()[b] - expected) < 1e-12);
            CHECK(glm::length(boundary.velocity(b) - (owner[k] == 0 ? v_sine : v_linear)) < 1e-12);
        }
        // The refreshed grid finds exactly what a brute-force search finds.
        const std::vector<Vec<2>> queries{sine.box_at(t).min + Vec<2>(-0.004, 0.05),
                                          sine.box_at(t).max + Vec<2>(0.006, -0.1),
                                          linear.box_at(t).min + Vec<2>(-0.006, 0.02)};
        NeighbourList found;
        boundary.find_neighbours(queries, found);
        for (std::size_t q = 0; q < queries.size(); ++q) {
            std::vector<std::uint32_t> got(found.of(q).begin(), found.of(q).end());
            std::vector<std::uint32_t> brute;
            for (std::uint32_t b = 0; b < boundary.size(); ++b)
                if (squared_length<2>(queries[q] - boundary.positions()[b]) < h * h)
                    brute.push_back(b);
            std::sort(got.begin(), got.end());
            CHECK(got == brute);
            CHECK(!brute.empty());
        }
    }
}

TEST_CASE("a paddle's particles follow it in a running simulation", "[paddle]") {
    json scene = piston_channel("dfsph");
    scene["effects"]["paddles"][0] = {{"min", {0.06, 0}}, {"max", {0.08, 0.2}},
                                      {"motion", "sine"}, {"amplitude", {0.04, 0}},
                                      {"period", 0.5},    {"start", 0.02}};
    Simulation<2> sim = make_simulation<2>(parse(scene));
    const BoundaryParticles<2>& boundary = *sim.boundary();
    const std::size_t first = boundary.moving_begin();
    REQUIRE(boundary.size() - first == 4 * 40);
    const std::vector<Vec<2>> rest(boundary.rest_positions().begin(),
                                   boundary.rest_positions().end());
    for (const Real t : {0.05, 0.1, 0.2}) {
        sim.advance_to(t);
        sim.update_fields(); // places the paddles at sim.time()
        const Vec<2> d = sim.params().paddles[0].displacement(sim.time());
        CHECK(std::abs(d.x - 0.04 * std::sin(2 * std::numbers::pi_v<Real> * (t - 0.02) / 0.5)) <
              1e-9);
        for (std::size_t k = 0; k < rest.size(); ++k)
            CHECK(glm::length(boundary.positions()[first + k] - (rest[k] + d)) < 1e-12);
        CHECK(inside_paddles(sim) == 0);
    }
}

TEST_CASE("a piston at constant speed pushes the fluid in front of it along", "[paddle]") {
    for (const std::string solver : {"dfsph", "wcsph"}) {
        DYNAMIC_SECTION(solver) {
            Simulation<2> sim = make_simulation<2>(parse(piston_channel(solver)));
            const Real piston = 0.2;
            Real momentum_x = 0;
            for (const Real t : {0.1, 0.2, 0.3}) {
                sim.advance_to(t);
                // Never inside the paddle, at any frame.
                CHECK(inside_paddles(sim) == 0);
            }
            // The fluid within 3 cm of the piston's face moves with it.
            const Real face = sim.params().paddles[0].box_at(sim.time()).max.x;
            Real near_sum = 0;
            std::size_t near = 0;
            for (std::size_t i = 0; i < sim.state().size(); ++i) {
                momentum_x += sim.params().mass * sim.state().velocity[i].x;
                if (sim.state().position[i].x < face + 0.03) {
                    near_sum += sim.state().velocity[i].x;
                    ++near;
                }
            }
            REQUIRE(near > 20);
            const Real near_mean = near_sum / Real(near);
            INFO("mean velocity of the fluid in front of the piston " << near_mean << " m/s");
            CHECK(near_mean == Approx(piston).epsilon(0.15));
            // The momentum it gave has the sign of the motion; without
            // gravity the fluid also rises in front of the piston, so the
            // block as a whole carries 0.55-0.6 of the piston's momentum
            // (measured, dfsph and wcsph), never more than all of it.
            const Real block_momentum = Real(sim.state().size()) * sim.params().mass * piston;
            INFO("momentum " << momentum_x << " against " << block_momentum);
            CHECK(momentum_x > 0.4 * block_momentum);
            CHECK(momentum_x < 1.05 * block_momentum);
        }
    }
}

TEST_CASE("a piston moving left pushes the fluid left", "[paddle]") {
    // The mirror image: the piston at the right end, moving towards -x.
    json scene = piston_channel("dfsph");
    scene["fluid"]["blocks"][0] = {{"min", {0.3, 0}}, {"max", {0.52, 0.1}}};
    scene["effects"]["paddles"][0] = {
        {"min", {0.52, 0}}, {"max", {0.54, 0.2}}, {"motion", "linear"}, {"velocity", {-0.2, 0}}};
    scene["effects"]["gravity"] = {0, -9.81};
    Simulation<2> sim = make_simulation<2>(parse(scene));
    sim.advance_to(0.2);
    Real momentum_x = 0;
    for (const Vec<2>& v : sim.state().velocity)
        momentum_x += sim.params().mass * v.x;
    CHECK(momentum_x < 0);
    CHECK(inside_paddles(sim) == 0);
}

TEST_CASE("a paddle the fluid never reaches changes nothing", "[paddle]") {
    // The moving part of the boundary is searched and summed after the
    // static part, and a static particle's velocity is exactly 0: fluid that
    // never comes near a paddle sees the same arithmetic as without it. With
    // a fixed step (the paddle's speed would otherwise shorten the adaptive
    // one) the state is the same bit for bit. Viscosity and artificial
    // viscosity are on, an obstacle is in the tank. wcsph's 2D cells are
    // made every step (cell_skin 0), as a paddle makes them: without one
    // they would serve several steps, other round-off.
    for (const std::string solver : {"dfsph", "wcsph"}) {
        DYNAMIC_SECTION(solver) {
            json scene = json::parse(R"({
                "domain": {"min": [0, 0], "max": [1.0, 0.3]},
                "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0], "max": [0.2, 0.2]}]},
                "material": {"viscosity": 0.01},
                "solver": {"dt": 0.0004, "cell_skin": 0},
                "effects": {"gravity": [0, -9.81], "artificial_viscosity": {"alpha": 0.05},
                            "obstacles": [{"box": {"min": [0.3, 0], "max": [0.34, 0.04]}}]}
            })");
            scene["solver"]["name"] = solver;
            json with_paddle = scene;
            with_paddle["effects"]["paddles"] = {{{"min", {0.8, 0}},
                                                  {"max", {0.82, 0.3}},
                                                  {"amplitude", {0.05, 0}},
                                                  {"period", 0.5}}};
            Simulation<2> plain = make_simulation<2>(parse(scene));
            Simulation<2> far = make_simulation<2>(parse(with_paddle));
            plain.advance_to(0.1);
            far.advance_to(0.1);
            CHECK(far.steps() == plain.steps());
            Snapshot a, b;
            copy_fields(plain.state(), a);
            copy_fields(far.state(), b);
            CHECK(state_hash(b) == state_hash(a));
        }
    }
}

TEST_CASE("the time step and the watchdog count the paddle's speed", "[paddle]") {
    json scene = piston_channel("dfsph");
    scene["effects"]["paddles"][0]["velocity"] = {3.0, 0};
    scene["effects"]["paddles"][0]["end"] = 0.01;
    const Scene parsed = parse(scene);
    const Derived derived = derive(parsed);
    json still = scene;
    still["effects"].erase("paddles");
    // Twice the sum of sound, fall and fastest start: the paddle's 3 m/s.
    CHECK(derived.max_speed == Approx(derive(parse(still)).max_speed + 2 * 3.0));
    Simulation<2> sim = make_simulation<2>(parsed);
    // dfsph: dt <= cfl spacing / v_max with the fluid at rest.
    CHECK(sim.next_dt() <= 0.4 * 0.005 / 3.0 * (1 + 1e-12));
}

TEST_CASE("bad paddles are refused with file and field", "[paddle]") {
    const json good = piston_channel("dfsph");
    REQUIRE_FALSE(error_of(good));
    json sine = good;
    sine["effects"]["paddles"][0] = {
        {"min", {0.06, 0}}, {"max", {0.08, 0.2}}, {"amplitude", {0.04, 0}}, {"period", 1}};
    REQUIRE_FALSE(error_of(sine));
    struct Case {
        json scene;
        std::string field, words;
    };
    const std::vector<Case> cases{
        {with(sine, "/effects/paddles/0/period", 0), "effects.paddles[0].period", ""},
        {with(sine, "/effects/paddles/0/amplitude", {0.07, 0}), "effects.paddles[0].amplitude",
         "outside the domain"},
        {with(sine, "/effects/paddles/0/max", {0.08, 0.25}), "effects.paddles[0]",
         "outside the domain"},
        {with(sine, "/effects/paddles/0/max", {0.062, 0.2}), "effects.paddles[0]",
         "thinner than one spacing"},
        {with(sine, "/effects/paddles/0/velocity", {1, 0}), "effects.paddles[0].velocity",
         "linear"},
        {with(sine, "/effects/paddles/0/motion", "flap"), "effects.paddles[0].motion", ""},
        {with(good, "/effects/paddles/0/velocity", {0, 0}), "effects.paddles[0].velocity",
         "not zero"},
        // 0.3 s at 0.2 m/s: 6 cm; 2 m/s leaves the domain.
        {with(good, "/effects/paddles/0/velocity", {2, 0}), "effects.paddles[0].velocity",
         "outside the domain"},
        {with(good, "/effects/paddles/0/amplitude", {0.01, 0}), "effects.paddles[0].amplitude",
         "sine"},
        {with(with(good, "/effects/paddles/0/start", 0.2), "/effects/paddles/0/end", 0.1),
         "effects.paddles[0].end", "after start"},
        {with(sine, "/solver/name", "seed"), "effects.paddles", "seed solver"},
    };
    for (const Case& c : cases) {
        const auto e = error_of(c.scene);
        INFO(c.scene.dump());
        REQUIRE(e);
        INFO(e->what());
        CHECK(e->field == c.field);
        CHECK(std::string(e->what()).find(c.words) != std::string::npos);
    }
}

TEST_CASE("a paddle's keys survive the round trip through run.json", "[paddle]") {
    json sine = piston_channel("wcsph");
    sine["effects"]["paddles"].push_back({{"min", {0.5, 0}},
                                          {"max", {0.52, 0.1}},
                                          {"amplitude", {-0.02, 0}},
                                          {"period", 0.7},
                                          {"start", 0.1}});
    const Scene a = parse(sine);
    const Scene b = parse(to_json(a));
    CHECK(to_json(a) == to_json(b));
    REQUIRE(b.effects.paddles.size() == 2);
    CHECK(b.effects.paddles[1].period == 0.7);
    CHECK(b.effects.paddles[0].motion == PaddleMotion::linear);
}
