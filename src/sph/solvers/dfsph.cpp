#include "sph/solvers/dfsph.hpp"

#include "sph/boundary.hpp"
#include "sph/density.hpp"
#include "sph/integrate.hpp"
#include "sph/pair_direction.hpp"
#include "sph/viscosity.hpp"

#include <algorithm>

// Notation. With g_ij = m grad W_ij (fluid pairs) and w_ib = rho0 V_b grad W_ib
// (wall pairs), the rate of compression is
//   D rho_i / Dt = sum_j g_ij . (v_i - v_j) + sum_b w_ib . v_i
// and a velocity correction with per-particle stiffness s
//   dv_i = - sum_j (s_i + s_j) g_ij - sum_b s_i w_ib
// is the symmetric pressure force with p_i / rho_i^2 = s_i / dt. Taking every
// s_j but s_i as zero, the correction changes D rho_i / Dt by -s_i S_i with
//   S_i = |sum_j g_ij + sum_b w_ib|^2 + sum_j |g_ij|^2,
// so s_i = (D rho_i / Dt) / S_i removes the divergence, and
// s_i = (rho*_i - rho0) / (dt S_i) the predicted compression
// (Bender & Koschier 2017, sec. 3-4, with the density folded into s).
// Units: g in kg m^-(D+1), S in its square, s in m^(D+2) / (kg s).

namespace sph {

template <int D>
template <class Kernel>
void DfsphSolver<D>::prepare(const Params<D>& params, const Kernel& kernel,
                             StepContext<D>& context, State<D>& state) {
    const std::size_t n = state.size();
    context.find_neighbours(state.position, params.h);
    compute_density(params, kernel, context.neighbours, state);
    if (context.boundary)
        add_boundary_density(params, kernel, *context.boundary, context.boundary_neighbours,
                             state);

    factor_.resize(n);
    stiffness_.resize(n);
    stiffness_sum_.resize(n);
    source_.resize(n);
    gradient_.resize(context.neighbours.pair_count());
    wall_gradient_.resize(context.boundary ? context.boundary_neighbours.pair_count() : 0);
    // No particle is compressed below a fraction of this: with S_i under it
    // (an isolated particle) there is nothing to push against.
    const Real tiny = 1e-9 * params.rest_density * params.rest_density / (params.h * params.h);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D> sum(0);
        Real sum_squares = 0;
        const std::uint32_t first = context.neighbours.start[i];
        for (std::uint32_t e = first; e < context.neighbours.start[i + 1]; ++e) {
            const std::uint32_t j = context.neighbours.index[e];
            const Vec<D> x_ij = state.position[i] - state.position[j];
            const Real r = std::sqrt(squared_length<D>(x_ij));
            const Vec<D> g = params.mass * pair_gradient(kernel, state, i, j, x_ij, r);
            gradient_[e] = g;
            sum += g;
            sum_squares += squared_length<D>(g);
        }
        if (context.boundary) {
            const auto xb = context.boundary->positions();
            const auto volume = context.boundary->volumes();
            const NeighbourList& walls = context.boundary_neighbours;
            for (std::uint32_t e = walls.start[i]; e < walls.start[i + 1]; ++e) {
                const std::uint32_t b = walls.index[e];
                const Vec<D> x_ib = state.position[i] - xb[b];
                const Real r = std::sqrt(squared_length<D>(x_ib));
                const Vec<D> w =
                    params.rest_density * volume[b] * boundary_gradient(kernel, x_ib, r);
                wall_gradient_[e] = w;
                sum += w;
            }
        }
        const Real S = squared_length<D>(sum) + sum_squares;
        factor_[i] = S > tiny ? 1 / S : 0;
    }
}

template <int D>
int DfsphSolver<D>::solve(const Params<D>& params, Real dt, Target target,
                          const StepContext<D>& context, State<D>& state) {
    const std::size_t n = state.size();
    const NeighbourList& pairs = context.neighbours;
    const NeighbourList* walls = context.boundary ? &context.boundary_neighbours : nullptr;
    const PressureSolveSettings& settings = params.pressure_solve;
    const Real tolerance = (target == Target::density ? settings.tolerance
                                                      : settings.divergence_tolerance) /
                           100;
    const Real rho0 = params.rest_density;
    int iterations = 0;
    for (;;) {
        // Compression rate with the current velocities; only compression is
        // corrected (a free surface may expand: Bender & Koschier 2017, sec. 4).
        Real error_sum = 0;
#pragma omp parallel for schedule(dynamic, 256) reduction(+ : error_sum)
        for (std::size_t i = 0; i < n; ++i) {
            Real rate = 0;
            for (std::uint32_t e = pairs.start[i]; e < pairs.start[i + 1]; ++e)
                rate += glm::dot(gradient_[e], state.velocity[i] - state.velocity[pairs.index[e]]);
            if (walls)
                for (std::uint32_t e = walls->start[i]; e < walls->start[i + 1]; ++e)
                    rate += glm::dot(wall_gradient_[e], state.velocity[i]);
            Real source;
            if (target == Target::density)
                source = std::max(state.density[i] + dt * rate - rho0, Real(0)) / dt;
            else
                source = std::max(rate, Real(0));
            source_[i] = source;
            error_sum += source;
        }
        // Mean relative compression (density) or compression within one step
        // (divergence): dt * mean(source) / rho0 in both cases.
        const Real error = n ? dt * error_sum / (Real(n) * rho0) : 0;
        if (target == Target::density)
            last_density_error_pct_ = 100 * error;
        const bool converged = error <= tolerance && iterations >= settings.min_iterations;
        if (converged || iterations >= settings.max_iterations)
            break;
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i)
            stiffness_[i] = source_[i] * factor_[i];
        // Gather: each particle corrects only its own velocity.
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D> dv(0);
            const Real s_i = stiffness_[i];
            for (std::uint32_t e = pairs.start[i]; e < pairs.start[i + 1]; ++e)
                dv -= (s_i + stiffness_[pairs.index[e]]) * gradient_[e];
            if (walls)
                for (std::uint32_t e = walls->start[i]; e < walls->start[i + 1]; ++e)
                    dv -= s_i * wall_gradient_[e];
            state.velocity[i] += dv;
            if (target == Target::density)
                stiffness_sum_[i] += s_i;
        }
        ++iterations;
    }
    return iterations;
}

template <int D>
StepReport DfsphSolver<D>::step(const Params<D>& params, Real dt, State<D>& state,
                                StepContext<D>& context) {
    StepReport report;
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        // 1. Neighbours, density (fluid + walls), the factors alpha_i.
        prepare(params, kernel, context, state);
        // 2. Divergence-free velocities (the previous step's end, Algorithm 1 line 12).
        report.divergence_iterations = solve(params, dt, Target::divergence, context, state);
        // 3. Non-pressure forces: viscosity and the scene's effects; v* = v + dt a.
        std::fill(state.acceleration.begin(), state.acceleration.end(), Vec<D>(0));
        if (params.viscosity > 0)
            add_laminar_viscosity(params, kernel, context.neighbours, context.boundary,
                                  context.boundary_neighbours, state);
    });
    apply_effects(context.effects, params, context.neighbours, state);
    kick(dt, state);
    // 4. Constant density: v so that rho* = rho0; p_i = rho_i^2 s_i / dt.
    std::fill(stiffness_sum_.begin(), stiffness_sum_.end(), Real(0));
    report.pressure_iterations = solve(params, dt, Target::density, context, state);
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        state.pressure[i] = state.density[i] * state.density[i] * stiffness_sum_[i] / dt;
    // 5. Move; the reflecting box stays behind the wall particles as a last guard.
    drift(dt, state);
    reflect_at_box(params, state);
    return report;
}

template <int D>
void DfsphSolver<D>::update_fields(const Params<D>& params, State<D>& state,
                                   StepContext<D>& context) {
    // Density at the current positions; pressure stays the last solve's.
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        context.find_neighbours(state.position, params.h);
        compute_density(params, kernel, context.neighbours, state);
        if (context.boundary)
            add_boundary_density(params, kernel, *context.boundary, context.boundary_neighbours,
                                 state);
    });
}

template class DfsphSolver<2>;
template class DfsphSolver<3>;

} // namespace sph
