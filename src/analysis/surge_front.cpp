#include "analysis/surge_front.hpp"

#include "analysis/csv_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

double surge_front_distance(const ParticleFrame& frame, double spacing, double x_wall) {
    const auto in_body = has_neighbour_within(frame, 2 * spacing);
    double front = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < frame.size(); ++i)
        if (in_body[i])
            front = std::max(front, frame.coordinate(i, 0));
    if (!std::isfinite(front))
        return std::numeric_limits<double>::quiet_NaN();
    return front + 0.5 * spacing - x_wall;
}

std::vector<SurgeSample> read_surge_reference(const std::filesystem::path& path) {
    const CsvTable table = read_csv_table(path);
    const auto& T = table.column("T");
    const auto& Z = table.column("Z");
    std::vector<SurgeSample> samples;
    for (std::size_t i = 0; i < table.rows(); ++i)
        if (std::isfinite(T[i]) && std::isfinite(Z[i]))
            samples.push_back({T[i], Z[i]});
    return samples;
}

double interpolate_Z(const std::vector<SurgeSample>& series, double T) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (series.empty() || T < series.front().T || T > series.back().T)
        return nan;
    const auto upper = std::lower_bound(series.begin(), series.end(), T,
                                        [](const SurgeSample& s, double t) { return s.T < t; });
    if (upper->T == T || upper == series.begin())
        return upper->Z;
    const auto lower = upper - 1;
    const double w = (T - lower->T) / (upper->T - lower->T);
    return lower->Z + w * (upper->Z - lower->Z);
}

SurgeComparison compare_surge_front(const std::vector<SurgeSample>& simulated,
                                    const std::vector<SurgeSample>& reference) {
    SurgeComparison result;
    double sum = 0;
    for (const auto& r : reference) {
        const double Z = interpolate_Z(simulated, r.T);
        if (std::isnan(Z))
            continue;
        result.points.push_back({r.T, r.Z, Z});
        sum += std::abs(Z - r.Z);
        result.max_abs_dZ = std::max(result.max_abs_dZ, std::abs(Z - r.Z));
    }
    if (result.points.empty()) {
        result.mean_abs_dZ = result.max_abs_dZ = std::numeric_limits<double>::quiet_NaN();
        return result;
    }
    result.mean_abs_dZ = sum / double(result.points.size());
    return result;
}

} // namespace sph
