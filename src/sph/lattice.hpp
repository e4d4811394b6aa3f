#pragma once
// Filling boxes with particles on a regular lattice, and the rest mass that
// makes such a lattice have exactly the rest density.

#include "sph/vec.hpp"

#include <cmath>
#include <cstddef>

namespace sph {

// Particles per axis in [min, max] at spacing s: at min + (k + 1/2) s, so the
// lattice sits half a spacing from each face. The tolerance keeps a box of
// exactly n spacings (up to rounding) at n particles.
inline std::size_t lattice_count(Real min, Real max, Real spacing) {
    const Real cells = (max - min) / spacing;
    return cells > 0 ? static_cast<std::size_t>(std::floor(cells + 1e-9)) : 0;
}

// Sum of W over a full lattice of spacing s around one of its points (the
// point itself included). A particle of mass rho0 / sum has density rho0 in
// the lattice's interior.
template <int D, class Kernel>
Real lattice_kernel_sum(const Kernel& kernel, Real spacing) {
    const int reach = static_cast<int>(std::ceil(kernel.h / spacing));
    Real sum = 0;
    if constexpr (D == 2) {
        for (int i = -reach; i <= reach; ++i)
            for (int j = -reach; j <= reach; ++j)
                sum += kernel.W(spacing * std::sqrt(Real(i * i + j * j)));
    } else {
        for (int i = -reach; i <= reach; ++i)
            for (int j = -reach; j <= reach; ++j)
                for (int k = -reach; k <= reach; ++k)
                    sum += kernel.W(spacing * std::sqrt(Real(i * i + j * j + k * k)));
    }
    return sum;
}

} // namespace sph
