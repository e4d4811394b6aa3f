#include "sph/diagnostics.hpp"

#include <algorithm>
#include <cmath>

namespace sph {

template <int D>
FrameStats measure_frame(const Params<D>& params, const State<D>& state) {
    FrameStats s;
    const std::size_t n = state.size();
    s.particles = n;
    if (n == 0)
        return s;
    Real density_sum = 0, error_sum = 0, speed2_sum = 0, speed2_max = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Real rho = state.density[i];
        const Real error = std::max(Real(0), (rho - params.rest_density) / params.rest_density);
        const Real speed2 = squared_length<D>(state.velocity[i]);
        density_sum += rho;
        s.density_max = std::max(s.density_max, rho);
        error_sum += error;
        s.density_error_max_pct = std::max(s.density_error_max_pct, 100 * error);
        speed2_sum += speed2;
        speed2_max = std::max(speed2_max, speed2);
    }
    s.density_avg = density_sum / Real(n);
    s.density_error_avg_pct = 100 * error_sum / Real(n);
    s.kinetic_energy = Real(0.5) * params.mass * speed2_sum;
    s.max_speed = std::sqrt(speed2_max);
    return s;
}

template FrameStats measure_frame<2>(const Params<2>&, const State<2>&);
template FrameStats measure_frame<3>(const Params<3>&, const State<3>&);

} // namespace sph
