// No allocation inside the step (issue: "No allocation inside the step"):
// once sizes settle, a step reuses the memory of the one before, whatever the
// solver, the search, the effects and the sorting of the particle arrays.
// Counted by replacing the global operator new for this test binary.
#include "scene/scene_setup.hpp"

#include <atomic>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <memory>
#include <new>
#include <omp.h>
#include <vector>

// The sanitizers bring their own operator new; the Release suite runs this.
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)

namespace {
std::atomic<bool> counting{false};
std::atomic<std::uint64_t> allocations{0};

void* counted_allocation(std::size_t size) {
    if (counting.load(std::memory_order_relaxed))
        allocations.fetch_add(1, std::memory_order_relaxed);
    if (void* p = std::malloc(size == 0 ? 1 : size))
        return p;
    throw std::bad_alloc();
}
} // namespace

void* operator new(std::size_t size) {
    return counted_allocation(size);
}
void* operator new[](std::size_t size) {
    return counted_allocation(size);
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
    try {
        return counted_allocation(size);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t size, const std::nothrow_t& tag) noexcept {
    return operator new(size, tag);
}
void operator delete(void* p) noexcept {
    std::free(p);
}
void operator delete[](void* p) noexcept {
    std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
    std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
    std::free(p);
}

using namespace sph;

namespace {

// Allocations made by `steps` steps after `warm_up` steps, on one thread:
// with more, libgomp allocates work-share records of its own when a thread
// lags behind the others (seen here under load, one now and then), which
// says nothing about our code.
std::uint64_t allocations_in_steps(const Scene& scene, int warm_up, int steps) {
    const int threads = omp_get_max_threads();
    omp_set_num_threads(1);
    auto sim = make_simulation<2>(scene);
    for (int k = 0; k < warm_up; ++k)
        sim.step();
    allocations = 0;
    counting = true;
    for (int k = 0; k < steps; ++k)
        sim.step();
    counting = false;
    omp_set_num_threads(threads);
    return allocations;
}

// A tank of water at rest across the whole floor of the built-in scene's box:
// nothing grows, so nothing should be allocated after the first steps.
std::vector<Override> tank(const char* solver, const char* search) {
    return {{"fluid.spacing", "0.005"},
            {"fluid.blocks", R"([{"min": [0, 0], "max": [0.4, 0.06]}])"},
            {"solver.name", solver},
            {"solver.neighbour_search", search}};
}

} // namespace

TEST_CASE("the allocation counter sees an allocation", "[simulation][memory]") {
    allocations = 0;
    counting = true;
    auto grown = std::make_unique<std::vector<double>>(1000);
    counting = false;
    CHECK(allocations == 2); // the vector and its elements
    CHECK(grown->size() == 1000);
}

TEST_CASE("a step allocates nothing once sizes settle", "[simulation][memory]") {
    // 30 warm-up steps take in the first sort of the arrays; the 45 counted
    // ones include two more (every 20 steps).
    for (const char* solver : {"seed", "wcsph", "dfsph"})
        for (const char* search : {"sorted_grid", "hash"}) {
            INFO(solver << ", " << search);
            CHECK(allocations_in_steps(default_scene(tank(solver, search)), 30, 45) == 0);
        }
}

TEST_CASE("a step with every effect allocates nothing once sizes settle", "[simulation][memory]") {
    // Laminar viscosity, artificial viscosity, XSPH and surface tension, on
    // wall particles; 100 warm-up steps, as the water settles against the
    // walls its contacts with them grow by more than the headroom.
    for (const char* solver : {"wcsph", "dfsph"}) {
        INFO(solver);
        std::vector<Override> o = tank(solver, "sorted_grid");
        o.insert(o.end(), {{"solver.walls", "particles"},
                           {"effects.gravity", "[0, -9.81]"},
                           {"effects.viscosity.model", "morris"},
                           {"effects.viscosity.mu", "0.01"},
                           {"effects.artificial_viscosity.alpha", "0.05"},
                           {"effects.xsph.epsilon", "0.1"},
                           {"effects.surface_tension.gamma", "0.07"}});
        CHECK(allocations_in_steps(default_scene(o), 100, 45) == 0);
    }
}

TEST_CASE("a flowing dam break allocates only as its sizes grow, seldom", "[simulation][memory]") {
    // The wall contacts and the grid's extent grow as the column collapses;
    // their arrays grow with a quarter of headroom, so 45 steps of the
    // collapse allocate a few times at most, never once per step.
    for (const char* solver : {"seed", "wcsph", "dfsph"}) {
        INFO(solver);
        const Scene scene = default_scene({{"fluid.spacing", "0.005"}, {"solver.name", solver}});
        CHECK(allocations_in_steps(scene, 30, 45) <= 4);
    }
}

#endif
