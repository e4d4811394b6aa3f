#include "sph/simulation.hpp"

#include "sph/boundaries/boundary_set.hpp"
#include "sph/surface.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <span>

namespace sph {

template <int D>
Simulation<D>::Simulation(const Params<D>& params, State<D> initial,
                          std::unique_ptr<Solver<D>> solver,
                          std::unique_ptr<NeighbourSearch<D>> search, EffectList<D> effects,
                          SourceList<D> sources, std::unique_ptr<Partition<D>> partition)
    : params_(params), state_(std::move(initial)), solver_(std::move(solver)),
      search_(std::move(search)), effects_(std::move(effects)), sources_(std::move(sources)),
      boundaries_(make_boundaries(params_)),
      // Over processes, none of the static ones until the partition says
      // where this one's particles are.
      boundary_(make_boundary_particles(params_, partition ? &walls_held_ : nullptr)),
      partition_(std::move(partition)) {
    if (partition_) {
        partition_->adopt(state_);
        partition_->cover_walls_with([this](const Box<D>& needed) { return cover_walls(needed); });
    }
    inspect_start();
}

template <int D>
std::size_t Simulation<D>::cover_walls(const Box<D>& needed) {
    if (!boundary_)
        return 0;
    // Laid again when the particles have left the box held, or when it has
    // grown much larger than they need (the ranks' boxes move and shrink).
    bool inside = true, oversized = false;
    Box<D> region;
    for (int a = 0; a < D; ++a) {
        inside =
            inside && walls_held_.min[a] <= needed.min[a] && needed.max[a] <= walls_held_.max[a];
        const Real extent = std::max<Real>(needed.max[a] - needed.min[a], 0);
        const Real margin = Real(0.1) * extent + 2 * params_.h;
        oversized = oversized || walls_held_.max[a] - walls_held_.min[a] > extent + 4 * margin;
        region.min[a] = needed.min[a] - margin;
        region.max[a] = needed.max[a] + margin;
    }
    if (!inside || oversized) {
        if (!obstacle_shells_)
            obstacle_shells_ = obstacle_shells(params_);
        std::optional<BoundaryParticles<D>> laid =
            make_static_boundary_particles(params_, &region, &*obstacle_shells_);
        if (laid)
            boundary_->replace_static(std::move(*laid));
        walls_held_ = region;
    }
    return boundary_->moving_begin();
}

template <int D>
void Simulation<D>::inspect_start() {
    if (particle_count() == 0)
        return;
    // Untimed: the stage times are the run's, which starts after this.
    auto ctx = context();
    ctx.stages = nullptr;
    ctx.place_boundaries(time_);
    if (partition_)
        partition_->update_fields(*solver_, params_, state_, ctx);
    else
        solver_->update_fields(params_, state_, ctx);
    // A compressed start (blocks overlapping, a mass too large for the
    // spacing) stores energy the equation of state turns into motion: what
    // it can release is physical speed the watchdog must allow. Only
    // compression counts: every free surface starts below rho0, where the
    // seed's linear law stores tension too, and the clumping it releases is
    // what the watchdog is there to catch.
    std::size_t densest = 0;
    for (std::size_t i = 0; i < state_.size(); ++i)
        if (state_.density[i] > state_.density[densest])
            densest = i;
    // The first densest particle in memory order: over processes, the
    // first process's that holds the largest density.
    struct {
        Real density;
        std::uint32_t id;
    } top{state_.size() ? state_.density[densest] : -std::numeric_limits<Real>::infinity(),
          state_.size() ? state_.id[densest] : 0};
    if (partition_) {
        Real largest = top.density;
        partition_->max(std::span(&largest, 1));
        const int from = partition_->lowest(top.density == largest ? 0 : 1);
        partition_->broadcast(std::as_writable_bytes(std::span(&top, 1)), from);
    }
    const Real rho = std::max(top.density, params_.rest_density);
    const Real energy = solver_->compression_energy(params_, rho);
    if (params_.watchdog.max_speed_adds_start_energy)
        params_.watchdog.max_speed += 2 * std::sqrt(2 * energy);
    start_density_ratio_ = top.density / params_.rest_density;
    start_densest_id_ = top.id;
}

template <int D>
std::string Simulation<D>::start_cause() const {
    // 10% above rest density: no liquid starts so compressed on purpose.
    if (start_density_ratio_ <= 1.1)
        return {};
    return fmt::format(
        "The fluid started compressed, particle {} at {:.3g} times the rest density (fluid "
        "blocks that overlap, or a fluid.mass too large for fluid.spacing): {} cannot follow "
        "the motion that compression releases. Start the fluid at its rest density.",
        start_densest_id_, start_density_ratio_, solver_->name());
}

template <int D>
Real Simulation<D>::next_dt() const {
    if (params_.time_step.fixed)
        return params_.time_step.dt;
    StageTimes::Scope timed(&stages_, Stage::time_step);
    ExtremeRates rates = measure_rates(state_);
    if (partition_) {
        Real extremes[3] = {rates.max_speed, rates.max_acceleration, rates.max_density};
        partition_->max(extremes);
        rates = {extremes[0], extremes[1], extremes[2]};
    }
    // What no particle shows yet: gravity before the first step, the speed
    // new particles enter with, the speed a paddle gives the fluid beside it.
    for (const auto& effect : effects_)
        rates.max_acceleration = std::max(rates.max_acceleration, effect->body_acceleration());
    for (const auto& source : sources_)
        rates.max_speed = std::max(rates.max_speed, source->speed());
    for (const auto& boundary : boundaries_)
        rates.max_speed = std::max(rates.max_speed, boundary->speed());
    TimeStepLimit limit = TimeStepLimit::dt_max;
    const Real dt = stable_time_step(params_, solver_->time_step_model(), rates,
                                     diffusion_viscosity(effects_), &limit);
    ++time_step_limits_[std::size_t(limit)];
    return dt;
}

template <int D>
std::optional<StepProblem> Simulation<D>::try_steps(Real dt, int count) {
    for (int k = 0; k < count; ++k) {
        auto ctx = context();
        ctx.dt = dt;
        ctx.start_time = time_ + Real(k) * dt;
        // The paddles where they are when the step starts.
        ctx.place_boundaries(ctx.start_time);
        const StepReport report = take_step(dt, ctx);
        ++steps_;
        ++counters_.steps;
        counters_.dt_min = std::min(counters_.dt_min, dt);
        counters_.dt_max = std::max(counters_.dt_max, dt);
        counters_.dt_sum += dt;
        counters_.pressure_iterations += report.pressure_iterations;
        counters_.divergence_iterations += report.divergence_iterations;
        counters_.obstacle_pushes += report.obstacle_pushes;
        StageTimes::Scope timed(&stages_, Stage::watchdog);
        if (auto problem = inspect_step(params_, state_, dt, partition_.get()))
            return problem;
    }
    return std::nullopt;
}

// The solver's step, or the partition's share of it. A step the solver
// asks to redo (dfsph's density solve ended above its tolerance) is taken
// again from its start as two halves, each of which may ask the same; the
// halves count as one step, with every attempt's iterations. Here rather
// than in the solver: over ranks each half starts from the gathered state,
// with a halo chosen where the first half left the particles.
template <int D>
StepReport Simulation<D>::take_step(Real dt, StepContext<D>& ctx) {
    StepReport report = partition_ ? partition_->step(*solver_, params_, dt, state_, ctx)
                                   : solver_->step(params_, dt, state_, ctx);
    if (!report.redo_in_halves)
        return report;
    const Real start = ctx.start_time;
    ++ctx.halvings;
    const StepReport first = take_step(dt / 2, ctx);
    ctx.start_time = start + dt / 2;
    ctx.place_boundaries(ctx.start_time);
    const StepReport second = take_step(dt / 2, ctx);
    --ctx.halvings;
    ctx.start_time = start;
    report.redo_in_halves = false;
    report.pressure_iterations += first.pressure_iterations + second.pressure_iterations;
    report.divergence_iterations += first.divergence_iterations + second.divergence_iterations;
    report.obstacle_pushes += first.obstacle_pushes + second.obstacle_pushes;
    return report;
}

template <int D>
void Simulation<D>::reorder_particles() {
    if (params_.reorder_every <= 0)
        return;
    // The first step sorts too: a scene's blocks are filled row by row.
    const bool due = steps_since_reorder_ == 0;
    steps_since_reorder_ = (steps_since_reorder_ + 1) % params_.reorder_every;
    if (!due)
        return;
    StageTimes::Scope timed(&stages_, Stage::reorder);
    if (partition_) {
        partition_->reorder(state_, params_.h);
        return;
    }
    // From the positions (and memory order) alone, never from the last
    // find's lists, so that frames and outputs cannot change the order.
    std::span<const std::uint32_t> order = search_->cell_order(state_.position, params_.h);
    if (order.size() != state_.size()) {
        if (!sorter_)
            sorter_ = make_neighbour_search<D>(NeighbourSearchKind::sorted_grid);
        order = sorter_->cell_order(state_.position, params_.h);
    }
    state_.permute(order, permute_scratch_);
    solver_->permute(order);
    for (const auto& effect : effects_)
        effect->permute(order);
}

template <int D>
void Simulation<D>::emit_particles() {
    for (const auto& source : sources_) {
        StageTimes::Scope timed(&stages_, StageName::of(*source));
        source->emit(params_, time_, state_, partition_.get());
    }
    // Over processes the new particles went to the last: the ranges are
    // cut again when they have grown uneven.
    if (partition_ && !sources_.empty()) {
        StageTimes::Scope timed(&stages_, Stage::reorder);
        partition_->rebalance(state_);
    }
}

template <int D>
void Simulation<D>::step_by(Real dt) {
    // Between steps, before anything is sized or saved for this one.
    reorder_particles();
    // The sources act first, outside the watchdog's retries, so a retried
    // step keeps what they added.
    emit_particles();
    // Over ranks, all of them: the partition's step fills the state from a
    // halo of its own, and the lighter save is tested on one process only.
    const StepInputs inputs = partition_ ? StepInputs{} : solver_->step_inputs(params_);
    {
        StageTimes::Scope timed(&stages_, Stage::watchdog);
        saved_.copy_from(state_, inputs);
    }
    const std::uint64_t steps_before = steps_;
    const StepCounters counters_before = counters_;
    for (int retry = 0;; ++retry) {
        const int pieces = 1 << retry;
        auto problem = try_steps(dt / Real(pieces), pieces);
        if (!problem)
            break;
        if (retry >= params_.watchdog.retries)
            throw UnstableError(steps_before + 1, time_, std::move(*problem), retry,
                                dt / Real(pieces), start_cause());
        state_.copy_from(saved_, inputs);
        steps_ = steps_before;
        counters_ = counters_before;
        counters_.retries += std::uint64_t(retry) + 1;
    }
    const std::size_t particles = particle_count();
    particle_steps_ += (steps_ - steps_before) * particles;
    const std::uint64_t pressure =
                            counters_.pressure_iterations - counters_before.pressure_iterations,
                        divergence =
                            counters_.divergence_iterations - counters_before.divergence_iterations;
    solve_work_.pressure_iterations += pressure;
    solve_work_.divergence_iterations += divergence;
    solve_work_.pressure += pressure * particles;
    solve_work_.divergence += divergence * particles;
    time_ += dt;
}

template <int D>
void Simulation<D>::step() {
    step_by(next_dt());
    // Fixed dt: time from the step count, so no rounding accumulates.
    if (params_.time_step.fixed)
        time_ = Real(++fixed_steps_) * params_.time_step.dt;
}

template <int D>
bool Simulation<D>::reached(Real t) const {
    const Real tolerance =
        1e-9 * (params_.time_step.fixed ? params_.time_step.dt : params_.time_step.dt_min);
    return time_ >= t - tolerance;
}

template <int D>
void Simulation<D>::step_toward(Real t) {
    if (params_.time_step.fixed) {
        step();
        return;
    }
    // Split what remains into equal steps no larger than the stable one, so
    // the last step is not a sliver; the final one lands on t exactly.
    const Real remaining = t - time_;
    const Real dt = next_dt();
    const Real count = std::ceil(remaining / dt - 1e-9);
    if (count <= 1) {
        step_by(remaining);
        time_ = t;
    } else {
        step_by(remaining / count);
    }
}

template <int D>
void Simulation<D>::advance_to(Real t) {
    while (!reached(t))
        step_toward(t);
}

template <int D>
void Simulation<D>::update_fields() {
    auto ctx = context();
    ctx.place_boundaries(time_);
    if (!partition_) {
        solver_->update_fields(params_, state_, ctx);
        return;
    }
    // Over processes: each computes its share's fields, then process 0,
    // which writes the frame's outputs, gets the whole state.
    partition_->update_fields(*solver_, params_, state_, ctx);
    StageTimes::Scope timed(&stages_, Stage::rank_gather);
    partition_->gather(state_, whole_);
}

template <int D>
void Simulation<D>::mark_buried(Real spacing, std::vector<std::uint8_t>& buried) {
    if (partition_)
        partition_->mark_buried(neighbours_, spacing, buried);
    else
        sph::mark_buried(state_, neighbours_, spacing, buried);
}

template <int D>
StepCounters Simulation<D>::take_counters() {
    StepCounters taken = counters_;
    counters_ = {};
    return taken;
}

template class Simulation<2>;
template class Simulation<3>;

} // namespace sph
