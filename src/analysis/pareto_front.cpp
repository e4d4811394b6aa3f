#include "analysis/pareto_front.hpp"

#include <cmath>

namespace sph {

std::vector<bool> pareto_optimal(const std::vector<CostAndError>& points) {
    auto valid = [](const CostAndError& p) {
        return std::isfinite(p.cost) && std::isfinite(p.error);
    };
    std::vector<bool> optimal(points.size(), false);
    // Studies have tens of runs: the quadratic check is clearer than a sweep.
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!valid(points[i]))
            continue;
        bool dominated = false;
        for (std::size_t j = 0; j < points.size() && !dominated; ++j) {
            if (j == i || !valid(points[j]))
                continue;
            const auto& a = points[j];
            const auto& b = points[i];
            dominated =
                a.cost <= b.cost && a.error <= b.error && (a.cost < b.cost || a.error < b.error);
        }
        optimal[i] = !dominated;
    }
    return optimal;
}

} // namespace sph
