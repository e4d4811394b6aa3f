// Whole simulations built from scenes: conservation, walls, frame timing,
// thread-count determinism (STYLE.md point 14) and the non-finite check.
#include "scene/scene_setup.hpp"
#include "sph/equation_of_state.hpp"
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
    auto sim = make_simulation<2>(small_dam_break({{"solver.dt", "0.0003"}}));
    sim.advance_to(0.001);
    CHECK(sim.steps() == 4); // 3 steps reach 0.0009, the 4th 0.0012
    CHECK(sim.time() == Approx(0.0012));
    sim.advance_to(0.0012); // already there
    CHECK(sim.steps() == 4);
    sim.advance_to(0.003); // exactly 10 steps, up to rounding
    CHECK(sim.steps() == 10);
    CHECK(sim.take_counters().retries == 0);
}

TEST_CASE("one thread and two threads give the same bits", "[simulation]") {
    // wcsph runs its single-precision cell passes by default; "wcsph double"
    // its double passes over neighbour lists; "wcsph carried" its carried
    // density (delta-SPH) and walls' pressure extrapolated from the fluid.
    for (const char* solver : {"seed", "wcsph", "dfsph", "wcsph double", "wcsph carried"}) {
        INFO(solver);
        const bool wcsph_double = std::string(solver) == "wcsph double";
        const bool carried = std::string(solver) == "wcsph carried";
        const Scene scene =
            small_dam_break({{"fluid.spacing", "0.0025"},
                             {"solver.name", wcsph_double || carried ? "wcsph" : solver},
                             {"solver.precision", wcsph_double ? "double" : "auto"},
                             {"solver.density_diffusion", carried ? "0.1" : "0"},
                             {"solver.wall_pressure", carried ? "extrapolated" : "mirror"}});
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
    try {
        sim.step();
        FAIL("no UnstableError");
    } catch (const UnstableError& e) {
        CHECK(e.step == 2);
        CHECK(e.time == Approx(1e-4)); // the time the failed step started from
        CHECK(e.retries == 4);         // the default watchdog.retries, all failed
        CHECK(e.dt == Approx(1e-4 / 16));
        CHECK(std::isnan(e.problem.value));
        CHECK((e.problem.quantity.starts_with("acceleration") ||
               e.problem.quantity.starts_with("velocity")));
        CHECK(std::string(e.what()).find("particle") != std::string::npos);
        CHECK(std::string(e.what()).find("Try a smaller solver.dt") != std::string::npos);
    }
}

namespace {

// A solver that moves particles at constant velocity and turns one NaN when
// its step is longer than `breaks_above`: a stand-in for a scheme that is
// stable only below some dt, so the watchdog's retries can be watched.
class FragileSolver final : public Solver<2> {
  public:
    explicit FragileSolver(Real breaks_above) : breaks_above_(breaks_above) {}
    std::string_view name() const override { return "fragile"; }
    TimeStepModel time_step_model() const override { return {}; }
    StepReport step(const Params<2>&, Real dt, State<2>& state, StepContext<2>&) override {
        ++calls;
        for (std::size_t i = 0; i < state.size(); ++i)
            state.position[i] += dt * state.velocity[i];
        if (dt > breaks_above_)
            state.velocity[3].x = std::numeric_limits<Real>::quiet_NaN();
        return {};
    }
    void update_fields(const Params<2>&, State<2>&, StepContext<2>&) override {}
    int calls = 0;

  private:
    Real breaks_above_;
};

Simulation<2> fragile_simulation(Real breaks_above, FragileSolver*& solver) {
    const Scene scene = small_dam_break({{"solver.dt", "0.004"}});
    const Derived derived = derive(scene);
    auto owned = std::make_unique<FragileSolver>(breaks_above);
    solver = owned.get();
    State<2> state = make_initial_state<2>(scene, derived);
    for (auto& v : state.velocity)
        v = {0.1, 0};
    for (auto& rho : state.density)
        rho = 1000;
    return Simulation<2>(make_params<2>(scene, derived), std::move(state), std::move(owned),
                         make_neighbour_search<2>("hash"), {});
}

} // namespace

TEST_CASE("the watchdog retries a failed step in halves from the saved state", "[simulation]") {
    FragileSolver* solver = nullptr;
    // Stable only at a quarter of the scene's fixed 4 ms: two retries (2 then 4 pieces).
    auto sim = fragile_simulation(0.0011, solver);
    const Vec<2> x0 = sim.state().position[0];
    sim.step();
    CHECK(solver->calls == 1 + 1 + 4); // a try stops at its first failed piece
    CHECK(sim.steps() == 4);           // only the accepted quarter steps count
    CHECK(sim.time() == Approx(0.004));
    // Restored and redone: the particle moved by the whole 4 ms, once.
    CHECK(sim.state().position[0].x == Approx(x0.x + 0.1 * 0.004));
    for (const auto& v : sim.state().velocity)
        CHECK(v.x == 0.1);
    const StepCounters counters = sim.take_counters();
    CHECK(counters.retries == 2);
    CHECK(counters.steps == 4);
    CHECK(counters.dt_max == Approx(0.001));
    // Fixed dt: frames still land on multiples of dt.
    sim.advance_to(0.012);
    CHECK(sim.time() == Approx(0.012));
    CHECK(sim.steps() == 12);
}

TEST_CASE("the watchdog stops when every retry fails, naming what and where", "[simulation]") {
    FragileSolver* solver = nullptr;
    auto sim = fragile_simulation(1e-6, solver); // 4 ms / 16 is still too long
    try {
        sim.step();
        FAIL("no UnstableError");
    } catch (const UnstableError& e) {
        CHECK(solver->calls == 5); // every try fails at its first piece
        CHECK(e.step == 1);
        CHECK(e.time == 0);
        CHECK(e.retries == 4);
        CHECK(e.dt == Approx(0.004 / 16));
        CHECK(e.problem.quantity == "velocity.x");
        CHECK(e.problem.particle == sim.state().id[3]);
        const std::string message = e.what();
        CHECK(message.find("step 1 ") != std::string::npos);
        CHECK(message.find("velocity.x") != std::string::npos);
        CHECK(message.find("retried 4 times") != std::string::npos);
    }
}

namespace {

// A solver as another, but for the state the watchdog saves: all of it.
template <int D>
class SavesAll final : public Solver<D> {
  public:
    explicit SavesAll(std::unique_ptr<Solver<D>> inner) : inner_(std::move(inner)) {}
    std::string_view name() const override { return inner_->name(); }
    TimeStepModel time_step_model() const override { return inner_->time_step_model(); }
    StepReport step(const Params<D>& params, Real dt, State<D>& state,
                    StepContext<D>& context) override {
        return inner_->step(params, dt, state, context);
    }
    void update_fields(const Params<D>& params, State<D>& state, StepContext<D>& context) override {
        inner_->update_fields(params, state, context);
    }
    Real compression_energy(const Params<D>& params, Real rho) const override {
        return inner_->compression_energy(params, rho);
    }
    void permute(std::span<const std::uint32_t> order) override { inner_->permute(order); }
    std::span<std::vector<Real>* const> kept_arrays() override { return inner_->kept_arrays(); }
    StepInputs step_inputs(const Params<D>&) const override { return {}; }

  private:
    std::unique_ptr<Solver<D>> inner_;
};

// The scene's simulation, its solver wrapped in SavesAll when `saves_all`.
template <int D>
Simulation<D> simulation_saving(const Scene& scene, bool saves_all) {
    const Derived derived = derive(scene);
    const Params<D> params = make_params<D>(scene, derived);
    std::unique_ptr<Solver<D>> solver = make_solver<D>(scene.solver.name, params);
    if (saves_all)
        solver = std::make_unique<SavesAll<D>>(std::move(solver));
    return Simulation<D>(params, make_initial_state<D>(scene, derived), std::move(solver),
                         make_neighbour_search<D>(scene.solver.neighbour_search),
                         make_effects<D>(scene), make_sources<D>(scene));
}

template <int D>
std::uint64_t hash_of(Simulation<D>& sim) {
    sim.update_fields();
    Snapshot frame;
    copy_fields(sim.state(), frame);
    return state_hash(frame);
}

} // namespace

// The watchdog saves only the arrays a step reads as the last one left them
// (Solver::step_inputs): a retried step must come out as from the whole
// saved state, while the arrays it did not save hold the failed try's.
TEST_CASE("a retried step is the same from the lighter saved state", "[simulation]") {
    // A fixed step, and at most 0.01 h a step: the fastest particles' steps
    // are retried in halves.
    const std::vector<Override> retried{
        {"solver.name", "wcsph"}, {"solver.dt", "2e-4"}, {"watchdog.max_displacement", "0.01"}};
    const auto check = [&](const std::vector<Override>& extra, auto dimension) {
        constexpr int D = decltype(dimension)::value;
        std::vector<Override> o = retried;
        o.insert(o.end(), extra.begin(), extra.end());
        const Scene scene = small_dam_break(o);
        auto light = simulation_saving<D>(scene, false);
        auto full = simulation_saving<D>(scene, true);
        light.advance_to(0.2);
        full.advance_to(0.2);
        CHECK(light.take_counters().retries > 0);
        CHECK(full.steps() == light.steps());
        CHECK(hash_of(light) == hash_of(full));
    };
    SECTION("symplectic Euler, double") {
        check({{"solver.precision", "double"}}, std::integral_constant<int, 2>{});
    }
    SECTION("symplectic Euler, single") {
        check({{"solver.precision", "single"}}, std::integral_constant<int, 2>{});
    }
    SECTION("Verlet") {
        check({{"solver.integrator", "verlet"}}, std::integral_constant<int, 2>{});
    }
    SECTION("a carried density") {
        check({{"solver.density_diffusion", "0.1"}}, std::integral_constant<int, 2>{});
    }
    SECTION("3D, single, each pair once") {
        check({{"dimension", "3"},
               {"domain.max", "[0.4,0.25,0.05]"},
               {"fluid.spacing", "0.008"},
               {"fluid.blocks", R"([{"min":[0,0,0],"max":[0.06,0.12,0.05]}])"},
               {"solver.precision", "single"}},
              std::integral_constant<int, 3>{});
    }
}

TEST_CASE("the watchdog flags a particle that jumps past its neighbourhood", "[simulation]") {
    const Scene scene = small_dam_break({{"solver.dt", "1e-4"}});
    auto sim = make_simulation<2>(scene);
    sim.step();
    const Real h = sim.params().h;
    // 2 h in one step of 10 ms (2.9 m/s, a plausible speed).
    sim.state().velocity[5] = {2 * h / 1e-2, 0};
    auto problem = inspect_step(sim.params(), sim.state(), 1e-2);
    REQUIRE(problem);
    CHECK(problem->quantity == "displacement / h");
    CHECK(problem->value == Approx(2));
    CHECK(problem->particle == sim.state().id[5]);
    // Faster than this scene's physics allows (twice sound speed + free fall).
    const Real limit = sim.params().watchdog.max_speed;
    CHECK(limit == Approx(2 * (std::sqrt(2e5 / 1000) + std::sqrt(2 * 9.81 * 0.4))));
    sim.state().velocity[5] = {0, 1.5 * limit};
    problem = inspect_step(sim.params(), sim.state(), 1e-7);
    REQUIRE(problem);
    CHECK(problem->quantity == "speed");
    CHECK(problem->value == Approx(1.5 * limit));
    sim.state().velocity[5] = {0, 0};
    sim.state().density[9] = 11 * scene.material.rest_density;
    problem = inspect_step(sim.params(), sim.state(), 1e-4);
    REQUIRE(problem);
    CHECK(problem->quantity == "density");
    CHECK(problem->limit == Approx(10 * scene.material.rest_density));
    sim.state().density[9] = scene.material.rest_density;
    CHECK_FALSE(inspect_step(sim.params(), sim.state(), 1e-4));
}

TEST_CASE("Tait's law stores 10/7 c^2 per kilogram at twice the rest density", "[simulation]") {
    Params<2> p;
    p.rest_density = 1000;
    p.bulk_modulus = 2e5;
    const Real c2 = p.bulk_modulus / p.rest_density;
    CHECK(compression_energy_tait(p, Real(2000)) == Approx(10.0 / 7 * c2));
    CHECK(compression_energy_tait(p, Real(1000)) == 0);
    CHECK(compression_energy_tait(p, Real(500)) == 0); // clamped: no tension
    // The linear law: c^2 (ln 2 - 1/2) at 2 rho0, and tension below rho0.
    CHECK(compression_energy_linear(p, Real(2000)) == Approx(c2 * (std::log(2.0) - 0.5)));
    CHECK(compression_energy_linear(p, Real(500)) == Approx(c2 * (std::log(0.5) + 1)));
}

TEST_CASE("the watchdog allows the speed a compressed start can release", "[simulation]") {
    // The block listed twice: every particle has a twin, twice the rest density.
    Scene scene = small_dam_break({{"solver.name", "wcsph"}});
    scene.fluid.blocks.push_back(scene.fluid.blocks.front());
    const Derived derived = derive(scene);
    auto sim = make_simulation<2>(scene, derived);
    Real densest = 0;
    for (Real rho : sim.state().density)
        densest = std::max(densest, rho);
    CHECK(densest == Approx(2 * scene.material.rest_density).epsilon(0.01));
    const Real released =
        std::sqrt(2 * compression_energy_tait(sim.params(), densest)); // about 1.7 c
    CHECK(sim.params().watchdog.max_speed == Approx(derived.max_speed + 2 * released));
    CHECK(released > derived.sound_speed);
    // wcsph lets it expand: the run goes on.
    sim.advance_to(0.02);
    CHECK(sim.time() == Approx(0.02));

    // A limit the scene sets is the limit.
    scene.watchdog.max_speed = 40;
    CHECK(make_simulation<2>(scene, derive(scene)).params().watchdog.max_speed == 40);

    // dfsph, incompressible, cannot start from it, and says so.
    scene.watchdog.max_speed.reset();
    scene.solver.name = SolverKind::dfsph;
    auto incompressible = make_simulation<2>(scene, derive(scene));
    CHECK(incompressible.params().watchdog.max_speed == Approx(derived.max_speed));
    try {
        incompressible.advance_to(0.02);
        FAIL("no UnstableError");
    } catch (const UnstableError& e) {
        const std::string message = e.what();
        INFO(message);
        CHECK(message.find("The fluid started compressed, particle ") != std::string::npos);
        CHECK(message.find(" at 2 times the rest density") != std::string::npos);
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

namespace {

// The stage table's rows by name, sorted; a part computed inside another
// stage as "name in stage".
std::vector<std::string> rows_of(const StageTimes& times) {
    std::vector<std::string> names;
    for (const auto& e : times.entries())
        names.push_back(e.within ? std::string(e.name) + " in " + std::string(stage_name(*e.within))
                                 : std::string(e.name));
    std::sort(names.begin(), names.end());
    return names;
}

} // namespace

TEST_CASE("the step times exactly the stages the scene asks for", "[simulation][stages]") {
    using Names = std::vector<std::string>;
    auto stages_of = [](const std::vector<Override>& o) {
        auto sim = make_simulation<2>(small_dam_break(o));
        for (int k = 0; k < 3; ++k)
            sim.step();
        CHECK(sim.particle_steps() == 3 * sim.state().size());
        return rows_of(sim.stage_times());
    };
    // The seed: reflecting walls, its pair force (pressure, then its viscous
    // term, the viscosity effect, in the same pass), gravity; the particles
    // sorted by cell on the first step (solver.reorder_every).
    CHECK(stages_of({}) == Names{"density", "gravity", "integration", "neighbour search",
                                 "pressure", "reorder", "time step", "viscosity in pressure",
                                 "walls", "watchdog"});
    // No effects and no viscosity: no gravity or viscosity stage. A fixed
    // step: no time-step rule. Never sorted: no reorder stage.
    CHECK(stages_of({{"effects", "{}"},
                     {"solver.dt", "1e-4"},
                     {"material.viscosity", "0"},
                     {"solver.reorder_every", "0"}}) ==
          Names{"density", "integration", "neighbour search", "pressure", "walls", "watchdog"});
    // wcsph: wall particles (found with the fluid's on grid cells in single
    // precision), Tait pressure, with Morris viscosity and the artificial one
    // it has by default in the same pass.
    CHECK(stages_of({{"solver.name", "wcsph"}}) ==
          Names{"artificial_viscosity in pressure", "density", "gravity", "integration",
                "neighbour search", "pressure", "reorder", "time step", "viscosity in pressure",
                "walls", "watchdog"});
    // Every viscosity effect named, with an inviscid material.
    CHECK(stages_of({{"solver.name", "wcsph"},
                     {"material.viscosity", "0"},
                     {"effects", R"({"viscosity": {"mu": 0.5, "model": "seed"},
                                     "artificial_viscosity": {"alpha": 0},
                                     "xsph": {"epsilon": 0.3}})"}}) ==
          Names{"boundary neighbours", "density", "integration", "neighbour search", "pressure",
                "reorder", "time step", "viscosity", "walls", "watchdog", "xsph"});
    // dfsph: its two solves, and its viscosities, Morris's and its default
    // artificial one, in one pass of their own.
    CHECK(stages_of({{"solver.name", "dfsph"}}) ==
          Names{"artificial_viscosity in viscosities", "boundary neighbours", "density",
                "divergence solve", "gravity", "integration", "neighbour search", "pressure solve",
                "reorder", "time step", "viscosities", "viscosity in viscosities", "walls",
                "watchdog"});
    // Without viscosity, the artificial one alone in that pass; with alpha
    // 0, no viscosity stage.
    CHECK(stages_of({{"solver.name", "dfsph"}, {"material.viscosity", "0"}}) ==
          Names{"artificial_viscosity in viscosities", "boundary neighbours", "density",
                "divergence solve", "gravity", "integration", "neighbour search", "pressure solve",
                "reorder", "time step", "viscosities", "walls", "watchdog"});
    CHECK(stages_of({{"solver.name", "dfsph"},
                     {"material.viscosity", "0"},
                     {"solver.artificial_viscosity", "0"}}) ==
          Names{"boundary neighbours", "density", "divergence solve", "gravity", "integration",
                "neighbour search", "pressure solve", "reorder", "time step", "walls", "watchdog"});
}

TEST_CASE("the stage table names each obstacle, paddle and emitter the scene declares, and "
          "nothing else",
          "[simulation][stages]") {
    using Names = std::vector<std::string>;
    // Algorithm stages come from the one table; every other row is a part
    // the scene declares, under its own key.
    const auto parts_of = [](const StageTimes& times) {
        Names parts;
        for (const auto& e : times.entries())
            if (std::find(stage_names.begin(), stage_names.end(), e.name) == stage_names.end())
                parts.emplace_back(e.name);
        std::sort(parts.begin(), parts.end());
        return parts;
    };
    const std::string obstacle_and_paddle =
        R"({"gravity": [0, -9.81],
            "obstacles": [{"box": {"min": [0.12, 0], "max": [0.14, 0.02]}}],
            "paddles": [{"min": [0.2, 0], "max": [0.21, 0.1], "motion": "sine",
                         "amplitude": [0.01, 0], "period": 0.5}]})";
    // (The seed's reflecting walls take no obstacles.)
    for (const char* solver : {"wcsph", "dfsph"}) {
        INFO(solver);
        auto sim = make_simulation<2>(small_dam_break({{"solver.name", solver},
                                                       {"material.viscosity", "0"},
                                                       {"effects", obstacle_and_paddle}}));
        for (int k = 0; k < 3; ++k)
            sim.step();
        // Both solvers' default artificial viscosity (wcsph's in its pressure pass).
        const Names declared{"artificial_viscosity", "gravity", "obstacles", "paddles", "walls"};
        CHECK(parts_of(sim.stage_times()) == declared);
        for (const auto& e : sim.stage_times().entries())
            if (e.name == "obstacles" || e.name == "paddles") {
                CHECK(!e.within);
                CHECK(e.seconds > 0);
            }
    }
    // An emitter is a part too; without obstacles or paddles they have no row.
    auto sim = make_simulation<2>(
        small_dam_break({{"material.viscosity", "0"},
                         {"effects", R"({"emitters": [{"min": [0.1, 0.1], "max": [0.112, 0.14],
                                       "velocity": [1, 0], "start": 0, "end": 1}]})"}}));
    for (int k = 0; k < 3; ++k)
        sim.step();
    CHECK(parts_of(sim.stage_times()) == Names{"emitters", "walls"});
}

TEST_CASE("a field no output reads is not computed, and the run is the same",
          "[simulation][fields]") {
    for (const char* solver : {"seed", "wcsph", "dfsph"}) {
        INFO(solver);
        const Scene scene = small_dam_break({{"solver.name", solver}});
        auto with = make_simulation<2>(scene);
        auto without = make_simulation<2>(scene);
        without.set_output_fields({.pressure = false});
        CHECK(with.output_fields().pressure);
        std::fill(without.state().pressure.begin(), without.state().pressure.end(), Real(-1));
        with.advance_to(0.02);
        without.advance_to(0.02);
        with.update_fields();
        without.update_fields();
        CHECK(with.state().position == without.state().position);
        CHECK(with.state().velocity == without.state().velocity);
        CHECK(with.state().density == without.state().density);
        const auto positive = [](const State<2>& s) {
            return std::any_of(s.pressure.begin(), s.pressure.end(), [](Real p) { return p > 0; });
        };
        CHECK(positive(with.state()));
        if (std::string(solver) == "dfsph") // its pressure is an output only: never written
            CHECK(std::all_of(without.state().pressure.begin(), without.state().pressure.end(),
                              [](Real p) { return p == -1; }));
        // A snapshot carries the pressure only when asked to.
        Snapshot frame;
        copy_fields(without.state(), frame, without.output_fields());
        CHECK(frame.pressure.empty());
        CHECK(frame.density.size() == without.state().size());
        copy_fields(with.state(), frame);
        CHECK(frame.pressure.size() == with.state().size());
    }
}
