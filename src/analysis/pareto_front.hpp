#pragma once
// Runs worth their cost: a run is Pareto-optimal when no other run is at least
// as cheap and at least as accurate, and strictly better in one of the two.

#include <vector>

namespace sph {

struct CostAndError {
    double cost = 0;  // e.g. wall-clock seconds; lower is better
    double error = 0; // lower is better
};

// One flag per point; a point with a NaN or infinite coordinate is never
// optimal and never dominates. Equal points are all optimal.
std::vector<bool> pareto_optimal(const std::vector<CostAndError>& points);

} // namespace sph
