#pragma once
// Particle state: one array per field (struct of arrays). Every array is listed
// in for_each_array, so resizing (and later emitting and spatial sorting)
// touches all of them. Arrays that only one solver or effect needs live in that
// solver or effect, not here.

#include "sph/vec.hpp"

#include <vector>

namespace sph {

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
        f(position);
        f(velocity);
        f(acceleration);
        f(density);
        f(pressure);
        f(id);
    }

    void resize(std::size_t n) {
        for_each_array([n](auto& array) { array.resize(n); });
    }
};

} // namespace sph
