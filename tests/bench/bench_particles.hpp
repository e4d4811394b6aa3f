#pragma once
// The particles the GL benchmarks draw (render_bench, composite_bench): a
// cube of fluid on a lattice, or a gas scattered in the same box.

#include "sph/neighbours/spatial_hash.hpp"
#include "sph/snapshot.hpp"
#include "sph/surface.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>

namespace sph::bench {

// n particles: a cube of fluid on a lattice, or uniformly scattered in the
// same box, with speeds that vary so the colour map is exercised; a block's
// buried particles are marked as a run marks them, from its neighbour lists.
inline Snapshot make_particles(std::size_t n, bool block, double spacing, double box) {
    Snapshot s;
    s.dimension = 3;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    const std::size_t side = std::size_t(std::ceil(std::cbrt(double(n))));
    s.position.reserve(3 * n);
    s.velocity.reserve(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        double x, y, z;
        if (block) {
            x = (double(i % side) + 0.5) * spacing;
            y = (double(i / side % side) + 0.5) * spacing;
            z = (double(i / side / side) + 0.5) * spacing;
        } else {
            x = u(rng) * box;
            y = u(rng) * box;
            z = u(rng) * box;
        }
        s.position.insert(s.position.end(), {x, y, z});
        s.velocity.insert(s.velocity.end(), {2 * y / box, 0, 0});
        s.density.push_back(1000);
        s.pressure.push_back(0);
        s.id.push_back(std::uint32_t(i));
    }
    if (block) {
        State<3> state;
        state.resize(n);
        for (std::size_t i = 0; i < n; ++i)
            state.position[i] = {s.position[3 * i], s.position[3 * i + 1], s.position[3 * i + 2]};
        NeighbourList list;
        SpatialHash<3>().find(state.position, 2.2 * spacing, list);
        mark_buried(state, list, spacing, s.buried);
    }
    return s;
}

} // namespace sph::bench
