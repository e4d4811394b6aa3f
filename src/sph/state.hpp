#pragma once
// Particle state: one array per field (struct of arrays). Every array is listed
// in for_each_array_with (for_each_array walks the same list), so resizing,
// emitting, the saved copy and the spatial sort (permute) touch all of them.
// Arrays that only one solver or effect needs live in that solver or effect,
// not here.

#include "sph/vec.hpp"

#include <cstdint>
#include <span>
#include <tuple>
#include <type_traits>
#include <vector>

namespace sph {

// Puts element order[k] of `array` at k; `scratch` takes the array's old
// memory, so that repeated calls allocate nothing once sizes settle. By
// all the threads: by one, the reorder was the one stage that did not run
// faster with two (SPlisHSPlasH's dam break, dfsph, which reorders every
// step: 0.029 s with 1 thread, 0.025 with 2).
template <class T>
void permute(std::vector<T>& array, std::span<const std::uint32_t> order, std::vector<T>& scratch) {
    scratch.resize(order.size());
    T* to = scratch.data();
    const T* from = array.data();
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < order.size(); ++k)
        to[k] = from[order[k]];
    array.swap(scratch);
}

// One scratch array per element type of State (see State::permute).
template <int D>
using PermuteScratch =
    std::tuple<std::vector<Vec<D>>, std::vector<Real>, std::vector<std::uint32_t>>;

// Which of a State's arrays a step reads as the step before left them,
// besides the positions, velocities and ids, which every step reads
// (Solver::step_inputs). The watchdog saves and restores only these: a step
// rebuilds the others before it reads them.
struct StepInputs {
    bool acceleration = true; // Verlet: the last step's, for the first kick
    bool density = true;      // a carried density (wcsph with delta-SPH)
    bool pressure = true;
};

template <int D>
struct State {
    std::vector<Vec<D>> position;     // m
    std::vector<Vec<D>> velocity;     // m/s
    std::vector<Vec<D>> acceleration; // m/s^2, rebuilt every step
    std::vector<Real> density;        // kg/m^3
    std::vector<Real> pressure;       // Pa
    // Identity of each particle from its creation, kept through any reordering,
    // so pair conventions and exports do not depend on memory order.
    std::vector<std::uint32_t> id;

    std::size_t size() const { return position.size(); }

    template <class F>
    void for_each_array(F&& f) {
        for_each_array_with(*this, [&f](auto& array, const auto&) { f(array); });
    }

    // This state's arrays beside `other`'s: the one list of the arrays.
    template <class F>
    void for_each_array_with(const State& other, F&& f) {
        f(position, other.position);
        f(velocity, other.velocity);
        f(acceleration, other.acceleration);
        f(density, other.density);
        f(pressure, other.pressure);
        f(id, other.id);
    }

    void resize(std::size_t n) {
        for_each_array([n](auto& array) { array.resize(n); });
    }

    // *this = other, copied by every thread a slice at a time: the state
    // saved before each step (Simulation::step_by), which one thread's copy
    // made the others wait for. Allocates nothing once sizes settle.
    // Only the arrays `inputs` names besides positions, velocities and ids:
    // the others are sized as other's and keep what they held (the full
    // copy was 3% of the 3D dam break's step).
    void copy_from(const State& other, StepInputs inputs = {}) {
        resize(other.size());
        const std::size_t n = other.size();
        const auto wanted = [&](const void* array) {
            return !((array == &acceleration && !inputs.acceleration) ||
                     (array == &density && !inputs.density) ||
                     (array == &pressure && !inputs.pressure));
        };
#pragma omp parallel
        for_each_array_with(other, [&](auto& to, const auto& from) {
            if (!wanted(&to))
                return;
#pragma omp for schedule(static) nowait
            for (std::size_t i = 0; i < n; ++i)
                to[i] = from[i];
        });
    }

    // Every array reordered so that particle order[k] comes to k (order is a
    // permutation of 0 .. size()-1); ids travel with their particles.
    void permute(std::span<const std::uint32_t> order, PermuteScratch<D>& scratch) {
        for_each_array([&](auto& array) {
            using Array = std::remove_reference_t<decltype(array)>;
            sph::permute(array, order, std::get<Array>(scratch));
        });
    }
};

} // namespace sph
