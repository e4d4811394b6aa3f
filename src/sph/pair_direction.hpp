#pragma once
// The direction from particle j to particle i, defined even when the two sit
// at the same place.

#include "sph/kernels.hpp"
#include "sph/state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace sph {

// A unit vector fixed by the pair's ids, for two particles at the same place:
// a kernel whose gradient does not vanish at r = 0 (spiky) still pushes them
// apart, along a direction that is the same on every run and opposite for the
// other particle.
template <int D>
Vec<D> coincident_direction(std::uint32_t id_a, std::uint32_t id_b) {
    // splitmix64 (Steele, Lea & Flood 2014) of the ordered pair.
    auto mix = [](std::uint64_t z) {
        z += 0x9e3779b97f4a7c15ull;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        return z ^ (z >> 31);
    };
    const std::uint64_t a = mix((std::uint64_t(id_a) << 32) | id_b);
    const std::uint64_t b = mix(a);
    const Real u = Real(a >> 11) * 0x1.0p-53; // uniform in [0, 1)
    const Real v = Real(b >> 11) * 0x1.0p-53;
    const Real angle = 2 * detail::pi * u;
    if constexpr (D == 2) {
        return {std::cos(angle), std::sin(angle)};
    } else {
        const Real z = 2 * v - 1;
        const Real ring = std::sqrt(1 - z * z);
        return {ring * std::cos(angle), ring * std::sin(angle), z};
    }
}

// x_ij / r, or for coincident particles (r below 1e-12 h) the pair's fixed
// direction, with the opposite sign for the other particle of the pair.
template <int D>
Vec<D> pair_direction(const State<D>& state, std::size_t i, std::size_t j, const Vec<D>& x_ij,
                      Real r, Real h) {
    if (r > 1e-12 * h)
        return x_ij / r;
    const std::uint32_t a = state.id[i], b = state.id[j];
    const Vec<D> d = coincident_direction<D>(std::min(a, b), std::max(a, b));
    return a > b ? -d : d;
}

// dW/dr / r, taken as 0 at r = 0 for a kernel whose value there is infinite
// (spiky); a smooth kernel's is computed without a condition, which keeps
// the loops that call it vectorised.
template <class Kernel>
Real gradient_factor(const Kernel& kernel, Real r) {
    if constexpr (Kernel::smooth_at_origin)
        return kernel.dW_over_r(r);
    else
        return r > 0 ? kernel.dW_over_r(r) : 0;
}

// grad_i W(x_i - x_j) for a fluid pair, defined at r = 0 as well.
template <int D, class Kernel>
Vec<D> pair_gradient(const Kernel& kernel, const State<D>& state, std::size_t i, std::size_t j,
                     const Vec<D>& x_ij, Real r) {
    if constexpr (Kernel::smooth_at_origin)
        return kernel.dW_over_r(r) * x_ij; // a product: the force loops vectorise
    else if (r > 1e-12 * kernel.h)
        return kernel.dW_over_r(r) * x_ij;
    else
        return kernel.dW(r) * pair_direction(state, i, j, x_ij, r, kernel.h);
}

// grad_i W(x_i - x_b) for a fluid particle and a boundary particle; a fluid
// particle exactly on a boundary particle is pushed along no direction in
// particular, so that pair contributes nothing (the reflecting box behind the
// wall keeps it in).
template <int D, class Kernel>
Vec<D> boundary_gradient(const Kernel& kernel, const Vec<D>& x_ib, Real r) {
    if constexpr (Kernel::smooth_at_origin)
        return kernel.dW_over_r(r) * x_ib;
    else
        return r > 1e-12 * kernel.h ? kernel.dW_over_r(r) * x_ib : Vec<D>(0);
}

} // namespace sph
