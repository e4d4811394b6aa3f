#pragma once
// Fixed parameters of one simulation, derived once from the scene and passed as
// `const Params&` to every stage. Changing quantities live in State.

#include "sph/vec.hpp"

namespace sph {

template <int D>
struct Params {
    Real mass = 0;         // kg, of every particle
    Real h = 0;            // m, support radius of the kernels
    Real rest_density = 0; // kg/m^3
    Real bulk_modulus = 0; // Pa, K in p = K (rho - rho0)
    Real viscosity = 0;    // Pa.s, dynamic viscosity mu
    Real dt = 0;           // s, fixed time step
    Box<D> domain;         // m, the walls particles reflect from
};

} // namespace sph
