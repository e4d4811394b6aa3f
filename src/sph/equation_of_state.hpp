#pragma once
// Equations of state: pressure from density.

#include "sph/params.hpp"
#include "sph/state.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

// The seed's linear law, with K a true bulk modulus in Pa (K = rho dp/drho):
//   p = K (rho - rho0) / rho0,   speed of sound c = sqrt(K / rho0).
// The seed writes p = K (rho - rho0) (Müller et al. 2003, eq. 12, a gas
// stiffness in m^2/s^2); its K is ours divided by rho0, the same model.
template <int D>
void compute_pressure_linear(const Params<D>& params, State<D>& state) {
    const std::size_t n = state.size();
    const Real stiffness = params.bulk_modulus / params.rest_density;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        state.pressure[i] = stiffness * (state.density[i] - params.rest_density);
}

// Energy per unit mass the linear law stores at density rho, J/kg: the work
// e = integral from rho0 to rho of p / rho'^2 drho' (it is positive on both
// sides of rho0: the law pulls as well as pushes).
template <int D>
Real compression_energy_linear(const Params<D>& params, Real rho) {
    const Real rho0 = params.rest_density;
    return params.bulk_modulus / rho0 * (std::log(rho / rho0) + rho0 / rho - 1);
}

// Tait's law as Becker & Teschner 2007 use it (eq. 7, after Monaghan 1994):
//   p = B ((rho / rho0)^7 - 1),  B = K / 7,
// so that dp/drho at rho0 is K / rho0 = c^2, the same sound speed as the
// linear law. A particle with too few neighbours (at the free surface) has
// a density below rho0; its pressure is clamped to zero instead of pulling
// its neighbours in, which would clump particles at the surface (the tensile
// instability).
template <int D>
void compute_pressure_tait(const Params<D>& params, State<D>& state) {
    const std::size_t n = state.size();
    const Real B = params.bulk_modulus / 7;
    const Real inverse_rest = 1 / params.rest_density;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
        const Real ratio = std::max(state.density[i] * inverse_rest, Real(1));
        const Real r2 = ratio * ratio;
        state.pressure[i] = B * (r2 * r2 * r2 * ratio - 1);
    }
}

// Energy per unit mass Tait's law stores at density rho, J/kg (the integral
// above; none below rho0, where the pressure is clamped to zero). At twice the
// rest density it is 10/7 c^2, at four times 97 c^2.
template <int D>
Real compression_energy_tait(const Params<D>& params, Real rho) {
    const Real rho0 = params.rest_density;
    if (rho <= rho0)
        return 0;
    const Real B = params.bulk_modulus / 7;
    return B * ((std::pow(rho / rho0, 6) - 1) / (6 * rho0) + 1 / rho - 1 / rho0);
}

} // namespace sph
