#pragma once
// Per-frame quantities of a run, and how far one run's series is from a
// reference run's: the accuracy of a study run when no experiment applies.

#include "analysis/particle_frames.hpp"

#include <vector>

namespace sph {

// A value (one or more components) per frame time.
struct FrameSeries {
    std::vector<double> time;                // s, increasing
    std::vector<std::vector<double>> values; // one vector per time
};

// Mean particle position (particles of one run have equal masses), m.
std::vector<double> centre_of_mass(const ParticleFrame& frame);

// y of the highest particle with another particle within 2 spacings (the
// body of the fluid, not a droplet), plus half a spacing. NaN for no fluid.
double surface_height(const ParticleFrame& frame, double spacing);

// RMS over the run's frame times inside the reference's time range of
// |run(t) - reference(t)| / scale, the reference interpolated linearly in t
// and the difference the Euclidean norm over components. NaN when no time of
// the run lies in the reference's range.
double rms_difference(const FrameSeries& run, const FrameSeries& reference, double scale);

} // namespace sph
