#pragma once
// The dam-break surge front in the dimensionless variables of Martin & Moyce
// (1952), "An experimental study of the collapse of liquid columns on a rigid
// horizontal plane", Phil. Trans. R. Soc. A 244: Z = x_front / a against
// T = t sqrt(2 g / a), a being the initial column width.

#include "analysis/particle_frames.hpp"

#include <filesystem>
#include <vector>

namespace sph {

struct SurgeSample {
    double T = 0; // t sqrt(2 g / a)
    double Z = 0; // x_front / a
};

// The front's distance from the left wall x_wall: the largest x among the
// particles with another particle within 2 spacings (spray is left out), plus
// half a spacing, the edge of that particle's lattice cell, so that the
// initial column gives exactly a.
double surge_front_distance(const ParticleFrame& frame, double spacing, double x_wall);

// Martin & Moyce's table: the columns T and Z of a CSV with '#' comments.
// Throws std::runtime_error for a missing file or column.
std::vector<SurgeSample> read_surge_reference(const std::filesystem::path& path);

// Z of `series` (increasing T) at T, linear between samples; NaN outside it.
double interpolate_Z(const std::vector<SurgeSample>& series, double T);

struct SurgeComparison {
    struct Point {
        double T, Z_reference, Z_simulated;
    };
    std::vector<Point> points; // the reference's T within the simulated range
    double mean_abs_dZ = 0;    // NaN when no reference T is in range
    double max_abs_dZ = 0;
};

// The simulation interpolated at every reference T it covers.
SurgeComparison compare_surge_front(const std::vector<SurgeSample>& simulated,
                                    const std::vector<SurgeSample>& reference);

} // namespace sph
