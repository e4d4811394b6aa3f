// The spatial sort of the particle arrays (State::permute,
// solver.reorder_every): a permutation that keeps every particle whole, that
// the solvers' own arrays follow, and that changes round-off only; a run with
// it is the same bits on 1 and 2 threads, and the exports do not see it.
#include "output/particle_export.hpp"
#include "scene/scene_setup.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/snapshot.hpp"
#include "sph/state_hash.hpp"
#include "support/temp_folder.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <fmt/format.h>
#include <numeric>
#include <omp.h>
#include <tuple>

using namespace sph;

namespace {

// The built-in dam break, coarse, with a fixed step so that runs with and
// without the sort take the same steps.
Scene dam_break(const std::vector<Override>& extra) {
    std::vector<Override> o{{"fluid.spacing", "0.0025"}, {"solver.dt", "2e-4"}};
    o.insert(o.end(), extra.begin(), extra.end());
    return default_scene(o);
}

// Index of each id (ids are 0 .. n-1).
template <int D>
std::vector<std::size_t> index_of_id(const State<D>& state) {
    std::vector<std::size_t> index(state.size(), state.size());
    for (std::size_t i = 0; i < state.size(); ++i) {
        REQUIRE(state.id[i] < state.size());
        index[state.id[i]] = i;
    }
    return index;
}

// Largest distance between the positions of the same particle in two states.
template <int D>
Real largest_gap(const State<D>& a, const State<D>& b) {
    REQUIRE(a.size() == b.size());
    const auto in_b = index_of_id(b);
    Real gap = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        gap = std::max(gap, glm::length(a.position[i] - b.position[in_b[a.id[i]]]));
    return gap;
}

State<2> scrambled_state(std::size_t n) {
    State<2> s;
    s.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const Real t = Real(i);
        // Spread over a few cells, not in any cell order.
        s.position[i] = {std::fmod(t * 0.37, 1.0), std::fmod(t * 0.61, 0.7)};
        s.velocity[i] = {t, -t};
        s.acceleration[i] = {2 * t, 3 * t};
        s.density[i] = 1000 + t;
        s.pressure[i] = 5 * t;
        s.id[i] = static_cast<std::uint32_t>(n - 1 - i);
    }
    return s;
}

} // namespace

TEST_CASE("a reorder is a permutation that keeps every particle whole", "[reorder]") {
    const State<2> before = scrambled_state(500);
    SortedGrid<2> grid;
    const std::span<const std::uint32_t> order = grid.cell_order(before.position, 0.1);
    REQUIRE(order.size() == before.size());
    std::vector<std::uint32_t> sorted(order.begin(), order.end());
    std::sort(sorted.begin(), sorted.end());
    std::vector<std::uint32_t> identity(before.size());
    std::iota(identity.begin(), identity.end(), 0u);
    CHECK(sorted == identity);
    CHECK_FALSE(std::equal(order.begin(), order.end(), identity.begin())); // it did sort

    State<2> after = before;
    PermuteScratch<2> scratch;
    after.permute(order, scratch);
    REQUIRE(after.size() == before.size());
    for (std::size_t k = 0; k < after.size(); ++k) {
        const std::size_t i = order[k];
        CHECK(after.id[k] == before.id[i]);
        CHECK(after.position[k] == before.position[i]);
        CHECK(after.velocity[k] == before.velocity[i]);
        CHECK(after.acceleration[k] == before.acceleration[i]);
        CHECK(after.density[k] == before.density[i]);
        CHECK(after.pressure[k] == before.pressure[i]);
    }
    // Neighbours in space are neighbours in memory: consecutive particles
    // are far closer after the sort than in the scrambled order.
    auto mean_step = [](const State<2>& s) {
        Real sum = 0;
        for (std::size_t k = 1; k < s.size(); ++k)
            sum += glm::length(s.position[k] - s.position[k - 1]);
        return sum / Real(s.size() - 1);
    };
    CHECK(mean_step(after) < 0.3 * mean_step(before));

    // The arrays and the scratch trade memory: another reorder allocates
    // nothing (the same buffers, in other hands).
    auto buffers = [&] {
        std::vector<const void*> all;
        after.for_each_array([&](auto& array) { all.push_back(array.data()); });
        std::apply([&](auto&... array) { (all.push_back(array.data()), ...); }, scratch);
        std::sort(all.begin(), all.end());
        return all;
    };
    const auto before_reorder = buffers();
    std::vector<std::uint32_t> reverse(after.size());
    std::iota(reverse.rbegin(), reverse.rend(), 0u);
    after.permute(reverse, scratch);
    CHECK(buffers() == before_reorder);
}

TEST_CASE("reordering changes the physics by round-off only", "[reorder]") {
    // wcsph on the sorted grid also in single precision, where a cell's
    // candidates come in memory order: float's round-off (6e-8), amplified.
    for (const char* solver : {"seed", "wcsph", "dfsph", "wcsph single"})
        for (const char* search : {"sorted_grid", "hash"}) {
            const bool single = std::string(solver) == "wcsph single";
            if (single && std::string(search) != "sorted_grid")
                continue;
            INFO(solver << " " << search);
            auto run = [&](const char* every) {
                auto sim = make_simulation<2>(
                    dam_break({{"solver.name", single ? "wcsph" : solver},
                               {"solver.neighbour_search", search},
                               {"solver.precision", single ? "single" : "double"},
                               {"solver.reorder_every", every}}));
                for (int k = 0; k < 20; ++k)
                    sim.step();
                return sim.state();
            };
            const State<2> never = run("0");
            const State<2> often = run("3");
            REQUIRE(never.size() > 500);
            // The sort did move particles in memory ...
            CHECK(never.id != often.id);
            // ... and the same particles are where they were without it: the
            // order of sums changed, by round-off (1e-16 relative) that 20
            // steps amplify to far below a nanometre. A particle that moved
            // 1 mm per step lost would be a million times further off.
            CHECK(largest_gap(never, often) < (single ? 1e-6 : 1e-9));
        }
}

TEST_CASE("dfsph's warm start follows the particles through a reorder", "[reorder]") {
    // One iteration per solve: the pressure is mostly the warm start, so a
    // warm start left in the old memory order would give every particle a
    // stranger's pressure.
    auto run = [](const char* every, int iterations) {
        auto sim =
            make_simulation<2>(dam_break({{"solver.name", "dfsph"},
                                          {"solver.warm_start", "true"},
                                          {"solver.min_iterations", std::to_string(iterations)},
                                          {"solver.max_iterations", std::to_string(iterations)},
                                          {"solver.reorder_every", every}}));
        for (int k = 0; k < 10; ++k)
            sim.step();
        return sim.state();
    };
    for (int iterations : {1, 100}) {
        INFO("iterations " << iterations);
        const State<2> never = run("0", iterations);
        const State<2> often = run("2", iterations);
        REQUIRE(never.id != often.id);
        const auto in_often = index_of_id(often);
        Real largest = 0, worst = 0;
        for (std::size_t i = 0; i < never.size(); ++i) {
            largest = std::max(largest, std::abs(never.pressure[i]));
            worst = std::max(worst,
                             std::abs(never.pressure[i] - often.pressure[in_often[never.id[i]]]));
        }
        REQUIRE(largest > 100); // Pa: the tank has a pressure to compare
        CHECK(worst < 1e-6 * largest);
        CHECK(largest_gap(never, often) < 1e-9);
    }
}

TEST_CASE("with reordering, one thread and two give the same bits", "[reorder]") {
    for (const char* solver : {"seed", "wcsph", "dfsph"})
        for (const char* search : {"sorted_grid", "hash"}) {
            INFO(solver << " " << search);
            const Scene scene = dam_break({{"solver.name", solver},
                                           {"solver.neighbour_search", search},
                                           {"solver.reorder_every", "4"},
                                           {"solver.dt", "1e-4"}});
            auto run = [&](int threads) {
                omp_set_num_threads(threads);
                auto sim = make_simulation<2>(scene);
                for (int k = 0; k < 30; ++k)
                    sim.step();
                return sim.state();
            };
            const int before = omp_get_max_threads();
            const State<2> one = run(1);
            const State<2> two = run(2);
            omp_set_num_threads(before);
            // The same memory order too: the sort reads positions only.
            CHECK(one.id == two.id);
            CHECK(one.position == two.position);
            CHECK(one.velocity == two.velocity);
            CHECK(one.density == two.density);
            CHECK(one.pressure == two.pressure);
        }
}

TEST_CASE("particle exports list particles by id, whatever the memory order", "[reorder]") {
    const State<2> state = scrambled_state(50);
    State<2> reversed = state;
    reversed.for_each_array([](auto& array) { std::reverse(array.begin(), array.end()); });
    Snapshot a, b;
    copy_fields(state, a);
    copy_fields(reversed, b);
    CHECK(state_hash(a) == state_hash(b));
    test::TempFolder one, two;
    std::filesystem::create_directories(one / "particles");
    std::filesystem::create_directories(two / "particles");
    ParticleCsv(one.path()).write(a);
    ParticleCsv(two.path()).write(b);
    ParticleVtk(one.path()).write(a);
    ParticleVtk(two.path()).write(b);
    for (const char* file : {"particles/frame_00000.csv", "particles/frame_00000.vtp"}) {
        INFO(file);
        CHECK(test::read_text(one / file) == test::read_text(two / file));
    }
    // The first row is id 0: the last particle in memory of `state`.
    const std::string csv = test::read_text(one / "particles/frame_00000.csv");
    const std::string first_row = csv.substr(csv.find('\n') + 1);
    CHECK(first_row.rfind(fmt::format("{:.9g},", state.position.back().x), 0) == 0);
}

TEST_CASE("emitted particles join a reordered state with ids of their own", "[reorder]") {
    // The emitter appends batches between sorts (dfsph, warm start on): every
    // particle keeps an id of its own, and no array of the old size (the warm
    // start's) trips a step.
    const Scene scene = load_scene(std::string(SPHCLIP_SOURCE_DIR) + "/scenes/emitter_fill_2d.json",
                                   {{"solver.reorder_every", "3"}, {"solver.warm_start", "true"}});
    auto sim = make_simulation<2>(scene);
    const std::size_t start = sim.state().size();
    sim.advance_to(0.05);
    const State<2>& s = sim.state();
    REQUIRE(s.size() > start); // batches came in
    std::vector<std::uint32_t> ids = s.id;
    std::sort(ids.begin(), ids.end());
    std::vector<std::uint32_t> expected(s.size());
    std::iota(expected.begin(), expected.end(), 0u);
    CHECK(ids == expected);
    const Box<2>& box = sim.params().domain;
    for (const auto& x : s.position)
        CHECK((x.x >= box.min.x && x.x <= box.max.x && x.y >= box.min.y && x.y <= box.max.y));
}

TEST_CASE("State::copy_from copies every array, with every thread", "[reorder]") {
    const State<2> source = scrambled_state(5000);
    // Into an empty state, a larger one and a smaller one.
    for (const std::size_t start : {std::size_t(0), std::size_t(7000), std::size_t(100)}) {
        INFO(start);
        State<2> copy;
        copy.resize(start);
        copy.for_each_array([](auto& array) {
            using T = typename std::decay_t<decltype(array)>::value_type;
            std::fill(array.begin(), array.end(), T(7));
        });
        copy.copy_from(source);
        CHECK(copy.size() == source.size());
        CHECK(copy.position == source.position);
        CHECK(copy.velocity == source.velocity);
        CHECK(copy.acceleration == source.acceleration);
        CHECK(copy.density == source.density);
        CHECK(copy.pressure == source.pressure);
        CHECK(copy.id == source.id);
    }
}

TEST_CASE("a cell order is the same whatever the threads that sort", "[reorder]") {
    // The counting sort shares the codes out among the threads it gets; a
    // call from inside a parallel region gets one, fewer than it asks for.
    const State<2> state = scrambled_state(5000);
    const int threads = omp_get_max_threads();
    omp_set_num_threads(2);
    SortedGrid<2> grid;
    const auto first = grid.cell_order(state.position, 0.1);
    const std::vector<std::uint32_t> order(first.begin(), first.end());
    std::vector<std::uint32_t> starts;
    for (std::size_t c = 0; c <= grid.cell_count(); ++c)
        starts.push_back(grid.cell_begin(c));
    std::vector<std::uint32_t> inner_order, inner_starts;
#pragma omp parallel num_threads(2)
#pragma omp single
    {
        const auto inner = grid.cell_order(state.position, 0.1);
        inner_order.assign(inner.begin(), inner.end());
        for (std::size_t c = 0; c <= grid.cell_count(); ++c)
            inner_starts.push_back(grid.cell_begin(c));
    }
    omp_set_num_threads(threads);
    CHECK(inner_order == order);
    CHECK(inner_starts == starts);
}

TEST_CASE("solver.reorder_every: each solver's default without the key, the key's value with it",
          "[reorder]") {
    const auto every = [](const std::vector<Override>& o) {
        return make_params<2>(default_scene(o), derive(default_scene(o))).reorder_every;
    };
    // dfsph builds neighbour lists each step, cheaper from arrays in cell
    // order (docs/benchmarks.md, "The pairs in slices").
    CHECK(every({{"solver.name", "dfsph"}}) == 1);
    CHECK(every({{"solver.name", "wcsph"}}) == 20);
    CHECK(every({{"solver.name", "seed"}}) == 20);
    CHECK(every({{"solver.name", "dfsph"}, {"solver.reorder_every", "7"}}) == 7);
    CHECK(every({{"solver.name", "wcsph"}, {"solver.reorder_every", "0"}}) == 0);
}
