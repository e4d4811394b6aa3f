#pragma once
// Numerical trouble is detected and named, never silently dropped: after every
// step the state is scanned for non-finite values.

#include "sph/state.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace sph {

struct NonFiniteError : std::runtime_error {
    std::uint64_t step;
    Real time;
    std::uint32_t particle; // the particle's id
    std::string quantity;
    Real value;
    NonFiniteError(std::uint64_t step, Real time, std::uint32_t particle, std::string quantity,
                   Real value);
};

// Throws NonFiniteError naming the first non-finite quantity found, in the
// order a step computes them (density, pressure, acceleration, velocity,
// position), so the name points at the stage where trouble began.
template <int D>
void check_finite(const State<D>& state, std::uint64_t step, Real time);

} // namespace sph
