#include "sph/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

template <int D>
ExtremeRates measure_rates(const State<D>& state) {
    Real v2 = 0, a2 = 0, rho = 0;
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static) reduction(max : v2, a2, rho)
    for (std::size_t i = 0; i < n; ++i) {
        v2 = std::max(v2, squared_length<D>(state.velocity[i]));
        a2 = std::max(a2, squared_length<D>(state.acceleration[i]));
        rho = std::max(rho, state.density[i]);
    }
    return {std::sqrt(v2), std::sqrt(a2), rho};
}

Real stable_time_step(const TimeStepSettings& ts, const TimeStepScales& scales, TimeStepModel model,
                      ExtremeRates rates, TimeStepLimit* limit) {
    Real dt = ts.dt_max;
    TimeStepLimit bound = TimeStepLimit::dt_max;
    const auto bind = [&](Real candidate, TimeStepLimit which) {
        if (candidate < dt) {
            dt = candidate;
            bound = which;
        }
    };
    if (model.carries_sound) {
        const Real compression = std::max(rates.max_density / scales.rest_density, Real(1));
        const Real c = scales.sound_speed * std::pow(compression, model.sound_speed_exponent);
        bind(ts.cfl * scales.h / (c + rates.max_speed), TimeStepLimit::sound);
    } else if (rates.max_speed > 0)
        bind(ts.cfl * scales.spacing / rates.max_speed, TimeStepLimit::particles);
    if (scales.viscosity > 0) {
        // Morris et al.'s h is the smoothing length, half our support radius.
        const Real smoothing = scales.h / 2;
        bind(0.125 * smoothing * smoothing * scales.rest_density / scales.viscosity,
             TimeStepLimit::viscosity);
    }
    if (rates.max_acceleration > 0)
        bind(0.25 * std::sqrt(scales.h / rates.max_acceleration), TimeStepLimit::forces);
    if (dt < ts.dt_min) {
        dt = ts.dt_min;
        bound = TimeStepLimit::dt_min;
    }
    if (limit)
        *limit = bound;
    return dt;
}

template ExtremeRates measure_rates<2>(const State<2>&);
template ExtremeRates measure_rates<3>(const State<3>&);

} // namespace sph
