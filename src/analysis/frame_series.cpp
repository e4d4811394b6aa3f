#include "analysis/frame_series.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

std::vector<double> centre_of_mass(const ParticleFrame& frame) {
    std::vector<double> com(frame.dimension, 0.0);
    for (std::size_t i = 0; i < frame.size(); ++i)
        for (int a = 0; a < frame.dimension; ++a)
            com[a] += frame.coordinate(i, a);
    for (double& c : com)
        c /= double(std::max<std::size_t>(frame.size(), 1));
    return com;
}

double surface_height(const ParticleFrame& frame, double spacing) {
    const auto in_body = has_neighbour_within(frame, 2 * spacing);
    double top = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < frame.size(); ++i)
        if (in_body[i])
            top = std::max(top, frame.coordinate(i, 1));
    return std::isfinite(top) ? top + 0.5 * spacing : std::numeric_limits<double>::quiet_NaN();
}

namespace {

// The reference at time t, linear between its frames; empty outside them.
std::vector<double> reference_at(const FrameSeries& ref, double t) {
    const auto& times = ref.time;
    if (times.empty() || t < times.front() || t > times.back())
        return {};
    const auto upper = std::lower_bound(times.begin(), times.end(), t);
    const std::size_t j = std::size_t(upper - times.begin());
    if (*upper == t || j == 0)
        return ref.values[j];
    const double w = (t - times[j - 1]) / (times[j] - times[j - 1]);
    std::vector<double> value(ref.values[j].size());
    for (std::size_t c = 0; c < value.size(); ++c)
        value[c] = ref.values[j - 1][c] + w * (ref.values[j][c] - ref.values[j - 1][c]);
    return value;
}

} // namespace

double rms_difference(const FrameSeries& run, const FrameSeries& reference, double scale) {
    // Frame times of runs with different time steps differ by up to one step:
    // a tolerance keeps the last frame of a run inside the reference's range.
    const double slack =
        reference.time.size() > 1 ? 1e-3 * (reference.time.back() - reference.time.front()) : 0.0;
    double squares = 0;
    std::size_t count = 0;
    for (std::size_t k = 0; k < run.time.size(); ++k) {
        double t = run.time[k];
        if (!reference.time.empty()) {
            if (t > reference.time.back() && t <= reference.time.back() + slack)
                t = reference.time.back();
            if (t < reference.time.front() && t >= reference.time.front() - slack)
                t = reference.time.front();
        }
        const auto ref = reference_at(reference, t);
        if (ref.empty())
            continue;
        double d2 = 0;
        for (std::size_t c = 0; c < ref.size() && c < run.values[k].size(); ++c)
            d2 += (run.values[k][c] - ref[c]) * (run.values[k][c] - ref[c]);
        if (!std::isfinite(d2))
            continue;
        squares += d2 / (scale * scale);
        ++count;
    }
    return count ? std::sqrt(squares / double(count)) : std::numeric_limits<double>::quiet_NaN();
}

} // namespace sph
