// Whole simulations built from scenes: conservation, walls, frame timing,
// thread-count determinism (STYLE.md point 14) and the non-finite check.
#include "io/scene_setup.hpp"
#include "sph/snapshot.hpp"
#include "sph/state_hash.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <omp.h>

using namespace sph;

namespace {

// The built-in dam break, coarse so that it runs in a moment.
Scene small_dam_break(const std::vector<Override>& extra = {}) {
    std::vector<Override> o{{"fluid.spacing", "0.005715"}};
    o.insert(o.end(), extra.begin(), extra.end());
    return default_scene(o);
}

template <int D>
bool inside(const Params<D>& p, const Vec<D>& x) {
    for (int a = 0; a < D; ++a)
        if (x[a] < p.domain.min[a] || x[a] > p.domain.max[a])
            return false;
    return true;
}

} // namespace

TEST_CASE("a dam break keeps every particle, inside the box", "[simulation]") {
    const Scene scene = small_dam_break();
    auto sim = make_simulation<2>(scene);
    const std::size_t n = sim.state().size();
    REQUIRE(n == 10 * 20);
    sim.advance_to(0.3);
    CHECK(sim.state().size() == n);
    std::vector<std::uint32_t> ids = sim.state().id;
    std::sort(ids.begin(), ids.end());
    for (std::size_t i = 0; i < n; ++i)
        CHECK(ids[i] == i);
    for (const auto& x : sim.state().position)
        CHECK(inside(sim.params(), x));
    // The column has collapsed to the right: the front moved away from the wall.
    Real front = 0;
    for (const auto& x : sim.state().position)
        front = std::max(front, x.x);
    CHECK(front > 2 * 0.05715);
}

TEST_CASE("a 3D drop keeps every particle inside the box", "[simulation]") {
    const Scene scene =
        default_scene({{"dimension", "3"},
                       {"domain.max", "[0.1,0.1,0.1]"},
                       {"fluid.spacing", "0.01"},
                       {"fluid.blocks", R"([{"min":[0.02,0.05,0.02],"max":[0.06,0.09,0.06]}])"}});
    auto sim = make_simulation<3>(scene);
    const std::size_t n = sim.state().size();
    REQUIRE(n == 64);
    sim.advance_to(0.2);
    CHECK(sim.state().size() == n);
    for (const auto& x : sim.state().position)
        CHECK(inside(sim.params(), x));
}

TEST_CASE("frames: advance_to stops at the first step at or past the time", "[simulation]") {
    auto sim = make_simulation<2>(small_dam_break({{"solver.dt", "0.003"}}));
    sim.advance_to(0.01);
    CHECK(sim.steps() == 4); // 3 steps reach 0.009, the 4th 0.012
    CHECK(sim.time() == Approx(0.012));
    sim.advance_to(0.012); // already there
    CHECK(sim.steps() == 4);
    sim.advance_to(0.03); // exactly 10 steps, up to rounding
    CHECK(sim.steps() == 10);
}

TEST_CASE("one thread and two threads give the same bits", "[simulation]") {
    for (const char* solver : {"seed", "wcsph", "dfsph"}) {
        INFO(solver);
        const Scene scene = small_dam_break({{"fluid.spacing", "0.0025"}, {"solver.name", solver}});
        auto run = [&](int threads) {
            omp_set_num_threads(threads);
            auto sim = make_simulation<2>(scene);
            for (int k = 0; k < 150; ++k)
                sim.step();
            return sim.state();
        };
        const int before = omp_get_max_threads();
        const auto one = run(1);
        const auto two = run(2);
        omp_set_num_threads(before);
        REQUIRE(one.size() > 500);
        CHECK(one.position == two.position);
        CHECK(one.velocity == two.velocity);
        CHECK(one.density == two.density);
        CHECK(one.pressure == two.pressure);
    }
}

TEST_CASE("a non-finite state stops the run and names the particle", "[simulation]") {
    auto sim = make_simulation<2>(small_dam_break({{"solver.dt", "1e-4"}}));
    sim.step();
    sim.state().velocity[7].y = std::numeric_limits<Real>::quiet_NaN();
    const Real expected_time = 2e-4;
    try {
        sim.step();
        FAIL("no NonFiniteError");
    } catch (const NonFiniteError& e) {
        CHECK(e.step == 2);
        CHECK(e.time == Approx(expected_time));
        CHECK(std::isnan(e.value));
        CHECK((e.quantity.starts_with("acceleration") || e.quantity.starts_with("velocity")));
        CHECK(std::string(e.what()).find("particle") != std::string::npos);
    }
}

TEST_CASE("a block without gravity or walls keeps its momentum and centre", "[simulation]") {
    // No effects and walls far away: the surface contracts (the seed's linear
    // law pulls where density is below rest), the block as a whole stays.
    const Scene scene =
        default_scene({{"effects", "{}"},
                       {"domain.min", "[-1,-1]"},
                       {"domain.max", "[1,1]"},
                       {"fluid.blocks", R"([{"min":[0,0],"max":[0.0200025,0.0200025]}])"}});
    auto sim = make_simulation<2>(scene);
    REQUIRE(sim.state().size() == 14 * 14);
    sim.advance_to(0.1);
    Vec<2> centre(0), momentum(0);
    Real speed_sum = 0;
    for (std::size_t i = 0; i < sim.state().size(); ++i) {
        centre += sim.state().position[i];
        momentum += sim.state().velocity[i];
        speed_sum += glm::length(sim.state().velocity[i]);
        CHECK(inside(sim.params(), sim.state().position[i]));
    }
    centre /= Real(sim.state().size());
    CHECK(centre.x == Approx(0.01000125).margin(1e-9));
    CHECK(centre.y == Approx(0.01000125).margin(1e-9));
    CHECK(glm::length(momentum) < 1e-12 * std::max(speed_sum, Real(1)));
}

TEST_CASE("the state hash sees every bit and not the memory order", "[simulation]") {
    auto sim = make_simulation<2>(small_dam_break());
    sim.advance_to(0.01);
    sim.update_fields();
    Snapshot a;
    copy_fields(sim.state(), a);
    const auto reference = state_hash(a);
    // The same particles in reverse memory order.
    State<2> reversed = sim.state();
    reversed.for_each_array([](auto& array) { std::reverse(array.begin(), array.end()); });
    Snapshot b;
    copy_fields(reversed, b);
    CHECK(state_hash(b) == reference);
    // One bit of one velocity.
    b.velocity[7] = std::nextafter(b.velocity[7], 1e9);
    CHECK(state_hash(b) != reference);
}
