#pragma once
// A column that starts hydrostatic (fluid.start = hydrostatic): what a column
// held at rest behind a gate already is when the gate goes, where a start at
// the rest density everywhere (fluid.start = rest) has zero pressure and
// spends its first depth / c in an acoustic settling the experiment did not
// have (the column falls, over-compresses to twice its hydrostatic pressure at
// the base, and springs back).
//
// The weakly compressible solvers find the density by summation, so the
// pressure is in the positions: a lattice particle at rest depth zeta (its
// depth in the uncompressed lattice) carries the weight of the mass above it,
// p = rho0 |g| zeta exactly, whatever the compression, so it must sit where
// the lattice is compressed to rho(p) through the solver's equation of state.
// The compressed depth is
//   d(zeta) = integral_0^zeta rho0 / rho(p(z)) dz
// which for the linear law rho / rho0 = 1 + p / K is
//   d = (K / (rho0 g)) ln(1 + rho0 g zeta / K)
// and for Tait's law rho / rho0 = (1 + p / B)^(1/7)
//   d = (7 B / (6 rho0 g)) ((1 + rho0 g zeta / B)^(6/7) - 1).
// DFSPH keeps the lattice as it is: the fluid is incompressible and its first
// density solve finds the hydrostatic pressure within the step.

#include "sph/vec.hpp"

#include <cmath>

namespace sph {

enum class FluidStart { rest, hydrostatic };

// How a solver's density answers pressure at rest.
enum class StartLaw { none, linear, tait };

// The compressed depth of a particle at rest depth zeta (m), for gravity g
// (m/s^2, > 0), rest density rho0 and bulk modulus K (Pa, c^2 = K / rho0).
inline Real compressed_depth(StartLaw law, Real zeta, Real g, Real rho0, Real K) {
    if (law == StartLaw::none || g <= 0 || zeta <= 0)
        return zeta;
    const Real weight = rho0 * g;
    if (law == StartLaw::linear)
        return (K / weight) * std::log1p(weight * zeta / K);
    const Real B = K / 7;
    return (7 * B / (6 * weight)) * (std::pow(1 + weight * zeta / B, Real(6) / 7) - 1);
}

// The density of a particle at rest depth zeta, rho(p) at p = rho0 |g| zeta:
// the start of a carried density (wcsph's delta-SPH), which a summation
// would give short at the floor's first rows, where the wall particles, not
// compressed with the lattice, make a third of the sum (measured: the bottom
// row at 72% of its pressure, pulled down at 2.4 g; docs/validation.md).
inline Real hydrostatic_density(StartLaw law, Real zeta, Real g, Real rho0, Real K) {
    if (law == StartLaw::none || g <= 0 || zeta <= 0)
        return rho0;
    const Real p = rho0 * g * zeta;
    if (law == StartLaw::linear)
        return rho0 * (1 + p / K);
    return rho0 * std::pow(1 + p / (K / 7), Real(1) / 7);
}

// The lattice site x of a block whose highest point along `up` is at height
// `top` and lowest at `bottom`: moved down along `up` so that the block's
// lowest point stays where it is and every site above it sits at its
// compressed depth below the (lowered) surface.
template <int D>
Vec<D> hydrostatic_site(const Vec<D>& x, const Vec<D>& up, Real top, Real bottom, StartLaw law,
                        Real g, Real rho0, Real K) {
    const Real zeta = top - glm::dot(x, up);
    const Real base = top - bottom;
    // How far the compression lowers a site at rest depth z, the base fixed.
    const Real drop = (base - compressed_depth(law, base, g, rho0, K)) -
                      (zeta - compressed_depth(law, zeta, g, rho0, K));
    return x - drop * up;
}

} // namespace sph
