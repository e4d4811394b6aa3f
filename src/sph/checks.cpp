#include "sph/checks.hpp"

#include <fmt/format.h>

namespace sph {

NonFiniteError::NonFiniteError(std::uint64_t step_, Real time_, std::uint32_t particle_,
                               std::string quantity_, Real value_)
    : std::runtime_error(fmt::format("simulation became non-finite at step {} (t = {:.6g} s): "
                                     "particle {} has {} = {}",
                                     step_, time_, particle_, quantity_, value_)),
      step(step_), time(time_), particle(particle_), quantity(std::move(quantity_)), value(value_) {
}

template <int D>
void check_finite(const State<D>& state, std::uint64_t step, Real time) {
    const std::size_t n = state.size();
    auto fail = [&](std::size_t i, const char* quantity, int axis, Real value) {
        static constexpr const char* axes = "xyz";
        std::string name = quantity;
        if (axis >= 0)
            name += fmt::format(".{}", axes[axis]);
        throw NonFiniteError(step, time, state.id[i], name, value);
    };
    // A cheap combined test first; the precise search runs only on failure.
    // Squared speeds are in it so that a velocity too large to square (the
    // kinetic energy would be infinite) counts as a blow-up too.
    Real sum = 0;
    for (std::size_t i = 0; i < n; ++i) {
        sum += state.density[i] + state.pressure[i] + squared_length<D>(state.velocity[i]);
        for (int a = 0; a < D; ++a)
            sum += state.acceleration[i][a] + state.velocity[i][a] + state.position[i][a];
    }
    if (std::isfinite(sum))
        return;
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(state.density[i]))
            fail(i, "density", -1, state.density[i]);
        if (!std::isfinite(state.pressure[i]))
            fail(i, "pressure", -1, state.pressure[i]);
    }
    for (const auto* field : {&state.acceleration, &state.velocity, &state.position}) {
        const char* name = field == &state.acceleration ? "acceleration"
                           : field == &state.velocity   ? "velocity"
                                                        : "position";
        for (std::size_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a)
                if (!std::isfinite((*field)[i][a]))
                    fail(i, name, a, (*field)[i][a]);
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Real speed2 = squared_length<D>(state.velocity[i]);
        if (!std::isfinite(speed2))
            fail(i, "speed squared", -1, speed2);
    }
    // The sum overflowed although every value is finite: values are huge.
    throw NonFiniteError(step, time, 0, "sum of all state values (overflow)", sum);
}

template void check_finite<2>(const State<2>&, std::uint64_t, Real);
template void check_finite<3>(const State<3>&, std::uint64_t, Real);

} // namespace sph
