#pragma once
// Shared by the render tests: particles on a lattice, as a snapshot.

#include "sph/snapshot.hpp"

#include <cstdint>

namespace sph::test {

// A lattice of side^3 (3D) or side^2 (2D) particles `spacing` apart from the
// origin, speeds varying with height so the colour map shows.
inline Snapshot lattice(int dimension, int side, double spacing) {
    Snapshot s;
    s.dimension = dimension;
    const int nz = dimension == 3 ? side : 1;
    for (int k = 0; k < nz; ++k)
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i) {
                const double x = (i + 0.5) * spacing, y = (j + 0.5) * spacing;
                s.position.insert(s.position.end(), {x, y});
                s.velocity.insert(s.velocity.end(), {y, 0});
                if (dimension == 3) {
                    s.position.push_back((k + 0.5) * spacing);
                    s.velocity.push_back(0);
                }
                s.density.push_back(1000);
                s.pressure.push_back(0);
                s.id.push_back(std::uint32_t(s.id.size()));
            }
    return s;
}

} // namespace sph::test
