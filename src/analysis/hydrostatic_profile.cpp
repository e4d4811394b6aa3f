#include "analysis/hydrostatic_profile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>

namespace sph {

double free_surface_height(const ParticleFrame& frame, double spacing) {
    const double width = 2 * spacing;
    std::map<std::pair<std::int64_t, std::int64_t>, double> top; // column -> highest y
    for (std::size_t i = 0; i < frame.size(); ++i) {
        const auto cx = std::int64_t(std::floor(frame.coordinate(i, 0) / width));
        const auto cz =
            frame.dimension == 3 ? std::int64_t(std::floor(frame.coordinate(i, 2) / width)) : 0;
        const double y = frame.coordinate(i, 1);
        const auto [it, inserted] = top.try_emplace({cx, cz}, y);
        if (!inserted)
            it->second = std::max(it->second, y);
    }
    double sum = 0;
    for (const auto& [column, y] : top)
        sum += y;
    return sum / double(top.size()) + 0.5 * spacing;
}

HydrostaticResult analyse_hydrostatic(const ParticleFrame& frame, const HydrostaticSetup& setup) {
    HydrostaticResult r;
    const std::size_t n = frame.size();
    if (n == 0)
        return r;
    r.surface = free_surface_height(frame, setup.spacing);
    r.fluid_depth = r.surface - setup.bottom;
    const double rho_g = setup.rest_density * setup.gravity;
    r.bottom_pressure = rho_g * r.fluid_depth;

    struct Sum {
        double depth = 0, pressure = 0;
        std::size_t count = 0;
    };
    std::map<std::int64_t, Sum> bins;
    double density_error = 0, speed_sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double depth = r.surface - frame.coordinate(i, 1);
        auto& bin = bins[std::int64_t(std::floor(depth / setup.spacing))];
        bin.depth += depth;
        bin.pressure += frame.pressure[i];
        ++bin.count;
        density_error += std::abs(frame.density[i] - setup.rest_density) / setup.rest_density;
        const double speed = frame.speed(i);
        speed_sum += speed;
        r.speed_max = std::max(r.speed_max, speed);
    }
    r.density_error_avg_pct = 100 * density_error / double(n);
    r.speed_mean = speed_sum / double(n);

    double squares = 0;
    for (const auto& [index, sum] : bins) {
        DepthBin bin;
        bin.particles = sum.count;
        bin.depth = sum.depth / double(sum.count);
        bin.pressure = sum.pressure / double(sum.count);
        bin.reference_pressure = rho_g * bin.depth;
        const double error = 100 * (bin.pressure - bin.reference_pressure) / r.bottom_pressure;
        squares += error * error;
        r.pressure_error_max_pct = std::max(r.pressure_error_max_pct, std::abs(error));
        r.bins.push_back(bin);
    }
    r.pressure_error_rms_pct = std::sqrt(squares / double(r.bins.size()));
    return r;
}

} // namespace sph
