#pragma once
// Equations of state: pressure from density.

#include "sph/params.hpp"
#include "sph/state.hpp"

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

} // namespace sph
