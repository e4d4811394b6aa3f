#include "analysis/gravity_current.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sph {

double huppert_front(double g, double area, double nu, double t) {
    return 1.411 * std::pow(g * area * area * area * t / (3 * nu), 0.2);
}

double spreading_half_width(const ParticleFrame& frame, double spacing) {
    const auto in_body = has_neighbour_within(frame, 2 * spacing);
    double low = std::numeric_limits<double>::infinity(), high = -low;
    for (std::size_t i = 0; i < frame.size(); ++i)
        if (in_body[i]) {
            low = std::min(low, frame.coordinate(i, 0));
            high = std::max(high, frame.coordinate(i, 0));
        }
    return (high - low + spacing) / 2;
}

} // namespace sph
