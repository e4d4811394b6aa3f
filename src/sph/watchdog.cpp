#include "sph/watchdog.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <span>
#include <utility>

namespace sph {

namespace {

std::string describe(const StepProblem& p) {
    if (std::isinf(p.limit))
        return fmt::format("particle {} has {} = {} (non-finite)", p.particle, p.quantity, p.value);
    return fmt::format("particle {} has {} = {:.6g}, above the limit {:.6g}", p.particle,
                       p.quantity, p.value, p.limit);
}

// What to change, by what went wrong.
std::string advice(const StepProblem& p) {
    if (p.quantity == "density")
        return "Try a smaller solver.cfl or solver.dt, more solver.max_iterations (dfsph), a "
               "larger material.bulk_modulus, or raise watchdog.max_density_ratio if the "
               "compression is meant.";
    if (p.quantity == "speed")
        return "The model cannot follow this flow: try a smaller material.bulk_modulus or a "
               "larger material.viscosity, another solver.name, or raise watchdog.max_speed if "
               "such speeds are meant.";
    return "Try a smaller solver.dt (or solver.cfl with the adaptive step), a smaller "
           "material.bulk_modulus, a larger material.viscosity, or more watchdog.retries.";
}

} // namespace

UnstableError::UnstableError(std::uint64_t step_, Real time_, StepProblem problem_, int retries_,
                             Real dt_, const std::string& cause)
    : std::runtime_error(
          fmt::format("simulation unstable at step {} (t = {:.6g} s): {}; the step was retried "
                      "{} times, halving it down to dt = {:.3g} s. {}{}{}",
                      step_, time_, describe(problem_), retries_, dt_, cause,
                      cause.empty() ? "" : " ", advice(problem_))),
      step(step_), time(time_), problem(std::move(problem_)), retries(retries_), dt(dt_) {}

namespace {

// The first problem of `state` in the order the checks are listed, with
// the check's place in that list; the maxima and the sum are the whole
// simulation's (over ranks, every rank's).
template <int D>
std::optional<std::pair<int, StepProblem>> find_problem(const Params<D>& params,
                                                        const State<D>& state, Real dt, Real sum,
                                                        Real max_density, Real max_speed2) {
    const std::size_t n = state.size();
    const Real density_limit = params.watchdog.max_density_ratio * params.rest_density;
    const Real speed_limit =
        std::min(params.watchdog.max_displacement * params.h / dt, params.watchdog.max_speed);
    constexpr Real infinite = std::numeric_limits<Real>::infinity();
    auto problem = [&](int check, std::size_t i, std::string quantity, Real value, Real limit) {
        return std::pair{check, StepProblem{state.id[i], std::move(quantity), value, limit}};
    };
    // In the order a step computes them, so the name points at the stage where
    // trouble began.
    for (std::size_t i = 0; i < n; ++i) {
        if (!std::isfinite(state.density[i]))
            return problem(0, i, "density", state.density[i], infinite);
        if (!std::isfinite(state.pressure[i]))
            return problem(0, i, "pressure", state.pressure[i], infinite);
    }
    static constexpr const char* axes = "xyz";
    int check = 1;
    for (const auto* field : {&state.acceleration, &state.velocity, &state.position}) {
        const char* name = field == &state.acceleration ? "acceleration"
                           : field == &state.velocity   ? "velocity"
                                                        : "position";
        for (std::size_t i = 0; i < n; ++i)
            for (int a = 0; a < D; ++a)
                if (!std::isfinite((*field)[i][a]))
                    return problem(check, i, fmt::format("{}.{}", name, axes[a]), (*field)[i][a],
                                   infinite);
        ++check;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const Real speed2 = squared_length<D>(state.velocity[i]);
        if (!std::isfinite(speed2))
            return problem(4, i, "speed squared", speed2, infinite);
    }
    if (!std::isfinite(sum))
        // Every value is finite but their sum overflowed: values are huge.
        return std::pair{5, StepProblem{0, "sum of all state values (overflow)", sum, infinite}};
    // The first particle (in memory order) at the worst value.
    for (std::size_t i = 0; i < n; ++i)
        if (squared_length<D>(state.velocity[i]) == max_speed2 &&
            max_speed2 > speed_limit * speed_limit)
            return speed_limit == params.watchdog.max_speed
                       ? problem(6, i, "speed", std::sqrt(max_speed2), speed_limit)
                       : problem(6, i, "displacement / h", std::sqrt(max_speed2) * dt / params.h,
                                 params.watchdog.max_displacement);
    for (std::size_t i = 0; i < n; ++i)
        if (state.density[i] == max_density && max_density > density_limit)
            return problem(7, i, "density", max_density, density_limit);
    return std::nullopt; // over ranks: another rank holds the problem
}

// A problem as bytes, to pass from the rank that found it to the others.
struct PackedProblem {
    std::uint32_t particle = 0;
    double value = 0, limit = 0;
    char quantity[64] = {};
};

} // namespace

template <int D>
std::optional<StepProblem> inspect_step(const Params<D>& params, const State<D>& state, Real dt,
                                        Collective* ranks) {
    const std::size_t n = state.size();
    const Real density_limit = params.watchdog.max_density_ratio * params.rest_density;
    const Real speed_limit =
        std::min(params.watchdog.max_displacement * params.h / dt, params.watchdog.max_speed);
    // One cheap pass: a sum that any non-finite value turns non-finite, and the
    // two maxima. The precise search below runs only when something is off.
    // Squared speeds are in the sum so that a velocity too large to square
    // counts as a blow-up too.
    Real sum = 0, max_density = 0, max_speed2 = 0;
#pragma omp parallel for schedule(static) reduction(+ : sum) reduction(max : max_density, max_speed2)
    for (std::size_t i = 0; i < n; ++i) {
        const Real speed2 = squared_length<D>(state.velocity[i]);
        sum += state.density[i] + state.pressure[i] + speed2;
        for (int a = 0; a < D; ++a)
            sum += state.acceleration[i][a] + state.position[i][a];
        max_density = std::max(max_density, state.density[i]);
        max_speed2 = std::max(max_speed2, speed2);
    }
    // Over ranks: the maxima are the whole simulation's; the sum is
    // non-finite when a rank's is (a sum that overflows only once the
    // ranks' are added is not seen: its values are near 1e308, and trip
    // another check first).
    if (ranks) {
        Real both[3] = {max_density, max_speed2, std::isfinite(sum) ? Real(0) : Real(1)};
        ranks->max(both);
        max_density = both[0];
        max_speed2 = both[1];
        sum = both[2] > 0 ? std::numeric_limits<Real>::infinity() : 0;
    }
    if (std::isfinite(sum) && max_density <= density_limit &&
        max_speed2 <= speed_limit * speed_limit)
        return std::nullopt;
    auto found = find_problem(params, state, dt, sum, max_density, max_speed2);
    if (!ranks)
        return found ? std::optional(found->second) : std::nullopt;
    // The first problem in the checks' order, the first rank's among equals:
    // the one a single process would name.
    const int winner = ranks->lowest(found ? found->first : std::numeric_limits<int>::max());
    PackedProblem packed;
    if (winner == ranks->rank() && found) {
        packed.particle = found->second.particle;
        packed.value = found->second.value;
        packed.limit = found->second.limit;
        found->second.quantity.copy(packed.quantity, sizeof packed.quantity - 1);
    }
    ranks->broadcast(std::as_writable_bytes(std::span(&packed, 1)), winner);
    return StepProblem{packed.particle, packed.quantity, packed.value, packed.limit};
}

template std::optional<StepProblem> inspect_step<2>(const Params<2>&, const State<2>&, Real,
                                                    Collective*);
template std::optional<StepProblem> inspect_step<3>(const Params<3>&, const State<3>&, Real,
                                                    Collective*);

} // namespace sph
