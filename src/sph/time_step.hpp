#pragma once
// The adaptive time step: the largest step the stability conditions allow,
// bounded by solver.dt_min and solver.dt_max.
//   - Courant-Friedrichs-Lewy: a signal crosses at most cfl of a length L per
//     step. Weakly compressible solvers carry sound, so dt <= cfl h / (c + v_max)
//     (Monaghan 1992, sec. 10.3), c the sound speed at the largest density; incompressible ones
//     only move particles, so dt <= cfl d / v_max with d the particle spacing (Bender & Koschier
//     2017, sec. 5, with their 0.4).
//   - Viscous diffusion: dt <= 0.125 l^2 / nu (Morris et al. 1997, eq. 11),
//     l their smoothing length, h / 2 (with l = h, a 500 Pa.s paste blew up
//     in the torture suite).
//   - Forces: dt <= 0.25 sqrt(h / a_max) (Monaghan 1992), with the
//     accelerations of the last step.

#include "sph/params.hpp"
#include "sph/state.hpp"

#include <array>
#include <cstdint>
#include <string_view>

namespace sph {

// What a solver tells the rule about itself.
struct TimeStepModel {
    bool carries_sound = true; // weakly compressible: the sound speed limits dt
    // How the sound speed grows with compression: c = c0 (rho / rho0)^n.
    // 0 for the linear law; (gamma - 1) / 2 = 3 for Tait's (c^2 = dp/drho),
    // whose sound speed at twice the rest density is 8 c0.
    Real sound_speed_exponent = 0;
};

// Largest |v| and |a| over the particles.
struct ExtremeRates {
    Real max_speed = 0;
    Real max_acceleration = 0;
    Real max_density = 0; // kg/m^3
};

template <int D>
ExtremeRates measure_rates(const State<D>& state);

// The fluid's figures the conditions need.
struct TimeStepScales {
    Real h = 0;            // m, support radius
    Real spacing = 0;      // m
    Real sound_speed = 0;  // m/s
    Real rest_density = 0; // kg/m^3
    Real viscosity = 0;    // Pa.s
};

// Which condition set a step (run.json "time_step_limits"): the one whose
// bound was the smallest, or the settings' ends.
enum class TimeStepLimit : std::uint8_t {
    dt_max,    // solver.dt_max: nothing moves fast enough to bind
    sound,     // cfl h / (c + v_max), weakly compressible solvers
    particles, // cfl spacing / v_max, incompressible solvers
    viscosity, // 0.125 l^2 / nu
    forces,    // 0.25 sqrt(h / a_max)
    dt_min,    // solver.dt_min: every condition asked for less
    count
};
// The names run.json uses, in the enum's order.
inline constexpr std::array<std::string_view, std::size_t(TimeStepLimit::count)>
    time_step_limit_names{"dt_max", "sound", "particles", "viscosity", "forces", "dt_min"};

// The step the conditions above allow for the given rates, within [dt_min,
// dt_max]; `limit`, when given, says which condition set it.
Real stable_time_step(const TimeStepSettings& settings, const TimeStepScales& scales,
                      TimeStepModel model, ExtremeRates rates, TimeStepLimit* limit = nullptr);

// `viscosity`: the largest mu by which an effect limits the step
// (diffusion_viscosity in effects/effect.hpp), 0 for none.
template <int D>
Real stable_time_step(const Params<D>& params, TimeStepModel model, ExtremeRates rates,
                      Real viscosity, TimeStepLimit* limit = nullptr) {
    return stable_time_step(
        params.time_step,
        {params.h, params.spacing, params.sound_speed(), params.rest_density, viscosity}, model,
        rates, limit);
}

} // namespace sph
