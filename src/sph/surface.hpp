#pragma once
// Which particles lie deep inside the fluid. A camera outside the fluid cannot
// see them behind opaque spheres, so the renderer may skip them.
//
// A particle is buried when, along each of the 2 D axis directions (+x, -x,
// +y, ...), some neighbour lies within 45 degrees of that direction and at
// least 1.5 spacings away: at least two layers of fluid cover it on every
// side. At a free surface the outward cone is empty, and one layer below it
// the cone holds only the surface layer (one spacing away), so the surface
// and the layer under it are always kept, however compressed the fluid. A
// neighbour-cone test in the spirit of the surface detection of
// Marrone et al. 2010 (sec. 2.2), reduced to what visibility needs.

#include "sph/neighbours/neighbour_list.hpp"
#include "sph/state.hpp"

#include <cstdint>
#include <vector>

namespace sph {

template <int D>
void mark_buried(const State<D>& state, const NeighbourList& neighbours, Real spacing,
                 std::vector<std::uint8_t>& buried) {
    const std::size_t n = state.size();
    buried.assign(n, 0);
    const Real min_distance2 = 2.25 * spacing * spacing;
    constexpr Real cos45 = 0.70710678118654752;
    constexpr unsigned all_directions = (1u << (2 * D)) - 1;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        unsigned covered = 0;
        for (std::uint32_t j : neighbours.of(i)) {
            const Vec<D> r = state.position[j] - state.position[i];
            const Real r2 = squared_length<D>(r);
            if (r2 < min_distance2)
                continue;
            const Real limit = cos45 * std::sqrt(r2);
            for (int a = 0; a < D; ++a) {
                if (r[a] >= limit)
                    covered |= 1u << (2 * a);
                else if (-r[a] >= limit)
                    covered |= 1u << (2 * a + 1);
            }
            if (covered == all_directions)
                break;
        }
        buried[i] = covered == all_directions;
    }
}

} // namespace sph
