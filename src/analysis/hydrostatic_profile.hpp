#pragma once
// A settled tank against hydrostatics: the pressure at depth d below the free
// surface is rho0 |g| d, the density is rho0 (to within rho0 |g| d / K, under
// 0.5% for the shipped scenes) and the fluid is at rest. Height is y: the
// scenes' gravity points along -y.

#include "analysis/particle_frames.hpp"

#include <cstddef>
#include <vector>

namespace sph {

struct HydrostaticSetup {
    double rest_density = 1000; // rho0, kg/m^3
    double gravity = 9.81;      // |g|, m/s^2
    double spacing = 0;         // particle spacing, m
    double bottom = 0;          // height of the tank's floor (domain.min.y), m
};

struct DepthBin {
    double depth = 0;              // mean depth of the bin's particles, m
    double pressure = 0;           // their mean pressure, Pa
    double reference_pressure = 0; // rho0 |g| depth, Pa
    std::size_t particles = 0;
};

struct HydrostaticResult {
    double surface = 0;         // estimated free-surface height, m
    double fluid_depth = 0;     // surface - bottom, m
    double bottom_pressure = 0; // rho0 |g| fluid_depth, Pa
    std::vector<DepthBin> bins; // one spacing deep each, from the surface down
    // Binned mean pressure minus rho0 |g| depth, in percent of bottom_pressure.
    double pressure_error_rms_pct = 0;
    double pressure_error_max_pct = 0;
    double density_error_avg_pct = 0; // mean |rho - rho0| / rho0 x 100
    double speed_max = 0;             // m/s
    double speed_mean = 0;            // m/s
};

// The free surface: the top particle of each column two spacings wide (two
// by two in 3D), averaged over the columns, plus half a spacing (the top of
// that particle's lattice cell). A mean over columns is steadier than the
// single highest particle, which one bump of the surface decides.
double free_surface_height(const ParticleFrame& frame, double spacing);

HydrostaticResult analyse_hydrostatic(const ParticleFrame& frame, const HydrostaticSetup& setup);

} // namespace sph
