#pragma once
// Per-frame figures written to stats.csv.

#include "sph/params.hpp"
#include "sph/state.hpp"

#include <cstddef>

namespace sph {

struct FrameStats {
    std::size_t particles = 0;
    Real density_avg = 0;           // kg/m^3
    Real density_max = 0;           // kg/m^3
    Real density_error_avg_pct = 0; // mean of max(0, (rho - rho0) / rho0) * 100
    Real density_error_max_pct = 0; // max of the same
    Real kinetic_energy = 0;        // J (per metre of depth in 2D)
    Real max_speed = 0;             // m/s
};

template <int D>
FrameStats measure_frame(const Params<D>& params, const State<D>& state);

} // namespace sph
