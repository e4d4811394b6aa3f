#include "sph/solvers/wcsph.hpp"

#include "sph/density_diffusion.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/pressure_acceleration.hpp"
#include "sph/solvers/density_with_walls.hpp"
#include "sph/wall_pressure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <type_traits>

namespace sph {

namespace {

// Density by summation over fluid and wall particles: in double on
// neighbour lists, or in float on grid cells.
template <int D, class Kernel>
void density(const Params<D>& params, const Kernel& kernel, StepContext<D>& context,
             SinglePasses<D>* single, const CellSkin<D>& skin, State<D>& state) {
    if (params.precision == Precision::double_precision) {
        find_neighbours_and_density(params, kernel, context, state);
        return;
    }
    SinglePasses<D>& cells = *single;
    {
        auto timed = context.time(Stage::neighbour_search);
        cells.find_cells(state.position, context.boundary, params.h, params.pair_terms, skin);
    }
    auto timed = context.time(Stage::density);
    cells.density(params, params.kernel, context.boundary, state);
}

// Tait's pressure from the density.
template <int D>
void pressure(const Params<D>& params, StepContext<D>& context, State<D>& state) {
    auto timed = context.time(Stage::pressure);
    compute_pressure_tait(params, state);
}

// The density, then Tait's pressure.
template <int D, class Kernel>
void density_and_pressure(const Params<D>& params, const Kernel& kernel, StepContext<D>& context,
                          SinglePasses<D>* single, const CellSkin<D>& skin, State<D>& state) {
    density(params, kernel, context, single, skin, state);
    pressure(params, context, state);
}

} // namespace

template <int D>
CellSkin<D> WcsphSolver<D>::cell_skin(const Params<D>& params, const State<D>& state,
                                      StepContext<D>& context) {
    const Real widest = params.cell_skin * params.h;
    if (!cell_skin_ || !(widest > 0) || params.precision != Precision::single ||
        (context.boundary && context.boundary->has_moving())) {
        cells_made_ = false;
        return {};
    }
    auto timed = context.time(Stage::neighbour_search);
    const std::size_t n = state.size();
    const bool same_particles = made_at_[0].size() == n;
    if (!same_particles)
        cells_made_ = false;
    // Cells made without a skin served one step: made again now.
    const bool certain = !same_particles || !(skin_width_ > 0);
    // Copies of the positions: where the cells are made, and the same as
    // points for the passes. In one parallel region, as few as the step
    // needs: a region's start costs as much as the copies of a few
    // thousand particles.
    const auto record = [&](bool made_at, bool points, bool measure) {
        Real most = 0;
        if (made_at)
            for (int a = 0; a < D; ++a)
                made_at_[std::size_t(a)].resize(n);
        if (points)
            made_at_points_.resize(n);
#pragma omp parallel for schedule(static) reduction(max : most)
        for (std::size_t i = 0; i < n; ++i) {
            Real d2 = 0;
            for (int a = 0; a < D; ++a) {
                Real& at = made_at_[std::size_t(a)][i];
                if (measure) {
                    const Real d = state.position[i][a] - at;
                    d2 += d * d;
                }
                if (made_at)
                    at = state.position[i][a];
                if (points)
                    made_at_points_[i][a] = at;
            }
            most = std::max(most, d2 == d2 ? d2 : std::numeric_limits<Real>::infinity());
        }
        return most;
    };
    // The largest squared move since the cells were made; infinite for
    // other particles or a position that is not finite. In one process,
    // with the cells still made, from the passes' copy of the positions,
    // which it also sets.
    Real most = std::numeric_limits<Real>::infinity();
    bool recorded = false;
    if (same_particles && cells_made_ && !context.halo)
        most = single_passes().refresh_cells(state.position);
    else if (same_particles) {
        most = record(certain, false, true);
        recorded = certain;
    }
    // Every rank decides as one process does: on the whole set's largest move.
    if (context.halo)
        most = context.halo->max_over_ranks(most);
    // A pair within the support now was within it plus twice the largest
    // move when the cells were made: cells as wide as the support plus the
    // skin hold it while twice that move is under the skin.
    const bool remake = certain || !(4 * most < skin_width_ * skin_width_);
    ++steps_on_cells_;
    if (remake) {
        // The next cells' skin: solver.cell_skin where, at the pace the
        // fastest particle kept since the last were made (under half the
        // skin a step), they would serve a step more; else none (a sound
        // speed near the flow's: a skin would cost candidates and save no
        // build; measured on dam_break_water_2d, docs/benchmarks.md).
        const Real pace = steps_on_cells_ > 0 && std::isfinite(most)
                              ? std::sqrt(most) / Real(steps_on_cells_)
                              : 0;
        skin_width_ = pace > 0 && 2 * pace > widest ? 0 : widest;
        steps_on_cells_ = 0;
        cells_made_ = false;
        if (!recorded)
            record(true, skin_width_ > 0, false);
        else if (skin_width_ > 0)
            record(false, true, false);
    }
    const bool keep = cells_made_ && !context.halo;
    // Cells made again from where they were made before (over ranks, every
    // step; in one process after a reordering or a frame's fields): the
    // points from made_at_, which follows the particles.
    if (!remake && !keep)
        record(false, true, false);
    // Without a skin the cells are made where the particles are (where
    // made_at_ now has them too): they serve this step only.
    cells_made_ = skin_width_ > 0;
    if (!(skin_width_ > 0))
        return {};
    return {made_at_points_, skin_width_, keep};
}

template <int D>
void WcsphSolver<D>::permute(std::span<const std::uint32_t> order) {
    for (std::vector<Real>* kept : kept_)
        if (kept->size() == order.size())
            sph::permute(*kept, order, permute_scratch_);
    cells_made_ = false; // made in the old order
}

template <int D>
void WcsphSolver<D>::compute_accelerations(const Params<D>& params, State<D>& state,
                                           StepContext<D>& context) {
    // Monaghan's artificial viscosity and Morris's laminar one, when the
    // scene names them, join the pressure pass (pressure_acceleration.hpp):
    // the stage "pressure" then times them too.
    const auto* artificial = fused_effect<ArtificialViscosity<D>>(context.effects);
    const auto* laminar = fused_effect<LaminarViscosity<D>>(context.effects);
    const MonaghanViscosity monaghan =
        artificial ? artificial->pair_viscosity(params) : MonaghanViscosity{};
    const MorrisViscosity morris = laminar ? laminar->pair_viscosity(params) : MorrisViscosity{};
    const PairViscosities viscosities{artificial ? &monaghan : nullptr,
                                      laminar ? &morris : nullptr};
    SinglePasses<D>* single = params.precision == Precision::single ? &single_passes() : nullptr;
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        // 1. Neighbours, density (fluid + walls, summed, or carried:
        // advance_carried), p = B ((rho / rho0)^7 - 1).
        if (params.density_diffusion > 0) {
            find_neighbours_and_carried_density(params, kernel, context, state);
            pressure(params, context, state);
        } else
            density_and_pressure(params, kernel, context, single, cell_skin(params, state, context),
                                 state);
        // Over ranks: the halo's densities and pressures from their owners.
        context.share_halo_densities(state);
        // 2. Pressure: a = -sum m (p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij) grad W,
        // walls included, and Morris's viscosity.
        if (params.precision == Precision::single) {
            auto timed = context.time(Stage::pressure);
            single->pressure_acceleration(params, kernel_, context.boundary, viscosities, state);
            return;
        }
        // The walls' own pressure, from the fluid's just computed.
        const Real* wall_term = nullptr;
        if (params.wall_pressure == WallPressure::extrapolated && context.boundary) {
            auto timed_walls = context.time(Stage::wall_pressure);
            extrapolate_wall_pressure(params, kernel, *context.boundary,
                                      context.boundary_neighbours, state, wall_pressure_);
            wall_term = wall_pressure_.pressure_term.data();
        }
        auto timed = context.time(Stage::pressure);
        compute_pressure_acceleration(params, kernel, context.neighbours, context.boundary,
                                      context.boundary_neighbours, viscosities, pressure_term_,
                                      state, wall_term);
    });
    // 3. The other effects the scene names: gravity, ... (in single
    // precision none that reads neighbour lists: the scene checks it).
    const std::array<const Effect<D>*, 2> merged{artificial, laminar};
    context.apply_effects(params, state, merged);
}

template <int D>
void WcsphSolver<D>::update_fields(const Params<D>& params, State<D>& state,
                                   StepContext<D>& context) {
    SinglePasses<D>* single = params.precision == Precision::single ? &single_passes() : nullptr;
    // A frame's fields from cells made where the particles are, as without
    // a skin (the next step makes its own again).
    cells_made_ = false;
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        if (params.density_diffusion > 0) {
            find_neighbours_and_carried_density(params, kernel, context, state);
            if (context.output_pressure)
                pressure(params, context, state);
        } else if (context.output_pressure)
            density_and_pressure(params, kernel, context, single, CellSkin<D>{}, state);
        else // the next step computes its own pressure
            density(params, kernel, context, single, CellSkin<D>{}, state);
    });
    // The outputs read the neighbour lists (3D culling of buried particles),
    // which single-precision steps do not build.
    if (params.precision == Precision::single)
        context.find_neighbours(state.position, params.h);
}

template <int D>
void WcsphSolver<D>::advance_carried(const Params<D>& params, Real dt, State<D>& state,
                                     StepContext<D>& context) {
    if (params.density_diffusion <= 0)
        return;
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        auto timed = context.time(Stage::density_rate);
        compute_density_rate(params, kernel, context.neighbours, context.boundary,
                             context.boundary_neighbours, state, continuity_, density_rate_);
    });
    auto timed = context.time(Stage::integration);
    const std::size_t n = state.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        state.density[i] += dt * density_rate_[i];
}

template class WcsphSolver<2>;
template class WcsphSolver<3>;

} // namespace sph
