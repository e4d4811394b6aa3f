#pragma once
// One simulation: fixed parameters, the particle state, and the parts a step is
// built from (solver, neighbour search, effects, boundaries and their
// particles, particle sources), all chosen once from the scene. Time advances by the adaptive step
// (time_step.hpp) or a fixed one; callers take frames at times they choose, which the steps land on
// exactly.

#include "sph/boundaries/boundary.hpp"
#include "sph/partition.hpp"
#include "sph/snapshot.hpp"
#include "sph/solvers/solver.hpp"
#include "sph/sources/source.hpp"
#include "sph/step_counters.hpp"
#include "sph/time_step.hpp"
#include "sph/watchdog.hpp"

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace sph {

template <int D>
class Simulation {
  public:
    // The boundaries are made here from params (walls, obstacles, paddles,
    // boundary_set.hpp), with their particles.
    // `partition`, when given, shares the simulation out over processes
    // (sph/partition.hpp): `initial` is then this process's share, the
    // partition's starting_share() of the initial state; state() is the
    // whole state as of the last update_fields().
    Simulation(const Params<D>& params, State<D> initial, std::unique_ptr<Solver<D>> solver,
               std::unique_ptr<NeighbourSearch<D>> search, EffectList<D> effects,
               SourceList<D> sources = {}, std::unique_ptr<Partition<D>> partition = {});

    // One step of the largest stable dt (or the fixed one). The watchdog
    // checks it; a failed step is retried from the state before it, split in
    // 2, 4, ... equal steps (watchdog.retries times), so that time still
    // advances by the same dt. Throws UnstableError when every retry fails.
    void step();
    // One step towards time t, shortened so that the steps land on t exactly.
    void step_toward(Real t);
    // Time t is reached (up to rounding).
    bool reached(Real t) const;
    // Steps until reached(t).
    void advance_to(Real t);
    // Density and pressure at the current positions, for output; the
    // paddles' particles are placed at time() first.
    void update_fields();
    // Which particles are buried (sph/surface.hpp's mark_buried) at the
    // last update_fields(), from its neighbour lists; over processes every
    // one must call it.
    void mark_buried(Real spacing, std::vector<std::uint8_t>& buried);
    // The fields the run's outputs read (all by default): a field no output
    // reads is not computed for output (dfsph's pressure, the pressure at
    // frame times).
    void set_output_fields(FrameFields fields) { output_fields_ = fields; }
    FrameFields output_fields() const { return output_fields_; }
    // The step the stability conditions allow now (the fixed one if fixed).
    Real next_dt() const;
    // Counters since the last call, then reset.
    StepCounters take_counters();
    // Steps shared out over processes (sph/partition.hpp); null: all here.
    const Partition<D>* partition() const { return partition_.get(); }

    const Params<D>& params() const { return params_; }
    // The particles: all of them. Over processes (a partition), on process
    // 0 the whole state gathered by the last update_fields(), the frames'
    // fields; on the others their share (a frame's own particles).
    const State<D>& state() const { return gathered() ? whole_ : state_; }
    State<D>& state() { return gathered() ? whole_ : state_; }
    // This process's particles (all of them in one process), the first of
    // state()'s.
    std::size_t share_size() const { return state_.size(); }
    // Particles now, over all processes.
    std::size_t particle_count() const {
        return partition_ ? partition_->total_particles() : state_.size();
    }
    const Solver<D>& solver() const { return *solver_; }
    const NeighbourSearch<D>& search() const { return *search_; }
    // Neighbours as the last step or update_fields() found them.
    const NeighbourList& neighbours() const { return neighbours_; }
    const EffectList<D>& effects() const { return effects_; }
    const SourceList<D>& sources() const { return sources_; }
    const BoundaryList<D>& boundaries() const { return boundaries_; }
    // Null when the walls reflect and there is no obstacle or paddle. The
    // paddles' particles are where the last step (or update_fields()) put them.
    const BoundaryParticles<D>* boundary() const { return boundary_ ? &*boundary_ : nullptr; }
    Real time() const { return time_; }
    // Time per stage since the start, and the particle-steps it was spent on
    // (accepted steps times the particles they moved).
    const StageTimes& stage_times() const { return stages_; }
    std::uint64_t particle_steps() const { return particle_steps_; }
    // The same for the iterative solves (dfsph): iterations times the
    // particles they ran over, summed over the accepted steps.
    SolveWork solve_work() const { return solve_work_; }
    std::uint64_t steps() const { return steps_; }
    // How many adaptive steps each stability condition set (time_step.hpp);
    // a watchdog's halving or a step cut to land on a frame counts as the
    // condition that chose the step it came from.
    const std::array<std::uint64_t, std::size_t(TimeStepLimit::count)>& time_step_limits() const {
        return time_step_limits_;
    }

  private:
    StepContext<D> context() {
        StepContext<D> ctx{*search_, neighbours_, boundary(), boundary_neighbours_,
                           effects_, boundaries_, &stages_};
        ctx.start_time = time_;
        ctx.output_pressure = output_fields_.pressure;
        if (boundary_ && boundary_->has_moving())
            ctx.moving_boundary = &*boundary_;
        return ctx;
    }
    // The fields at the start, and what they mean for the watchdog: the
    // speed limit grows by what the start's compression can release.
    void inspect_start();
    // Why a run that started compressed may have failed; empty otherwise.
    std::string start_cause() const;
    // Advances by dt under the watchdog (see step()).
    void step_by(Real dt);
    // The sources add the particles due by now (emitters).
    void emit_particles();
    // Every params.reorder_every steps: the particle arrays (the state's, the
    // solver's, the effects') sorted by cell, at the current positions.
    void reorder_particles();
    // One step of dt, in halves where the solver asks (see simulation.cpp).
    StepReport take_step(Real dt, StepContext<D>& ctx);
    // Over processes: makes the static boundary particles held cover
    // `needed` (Partition::cover_walls_with); how many it holds.
    std::size_t cover_walls(const Box<D>& needed);
    // Whether state() is the whole state gathered from the processes.
    bool gathered() const { return partition_ && partition_->rank() == 0; }
    // Plain steps, checked after each; the first problem found, if any.
    std::optional<StepProblem> try_steps(Real dt, int count);

    Params<D> params_;
    State<D> state_; // over processes, this one's share
    State<D> whole_; // over processes, on process 0: the whole state at the last update_fields()
    std::unique_ptr<Solver<D>> solver_;
    std::unique_ptr<NeighbourSearch<D>> search_;
    EffectList<D> effects_;
    SourceList<D> sources_;
    BoundaryList<D> boundaries_;
    // Over processes: the box whose static boundary particles boundary_
    // holds (none yet: empty).
    Box<D> walls_held_{Vec<D>(1), Vec<D>(0)};
    std::optional<BoundaryParticles<D>> boundary_;
    // Over processes: the obstacles' shells, sampled once, from which each
    // new box's are taken.
    std::optional<BoundarySamples<D>> obstacle_shells_;
    NeighbourList neighbours_;
    NeighbourList boundary_neighbours_;
    StepCounters counters_;
    State<D> saved_;                     // the state before the step, for the watchdog's retries
    Real start_density_ratio_ = 0;       // densest particle at the start, / rho0
    std::uint32_t start_densest_id_ = 0; // its id
    // The spatial sort: a grid of its own when the search keeps no cell
    // order (hash, all_pairs), made on first use; scratch for the permutation.
    std::unique_ptr<NeighbourSearch<D>> sorter_;
    PermuteScratch<D> permute_scratch_;
    std::unique_ptr<Partition<D>> partition_;
    int steps_since_reorder_ = 0;
    Real time_ = 0;
    std::uint64_t steps_ = 0;
    std::uint64_t fixed_steps_ = 0;
    std::uint64_t particle_steps_ = 0;
    SolveWork solve_work_;
    FrameFields output_fields_;
    mutable std::array<std::uint64_t, std::size_t(TimeStepLimit::count)> time_step_limits_{};
    mutable StageTimes stages_; // next_dt() const is timed too // fixed dt: time is this count
                                // times dt, free of rounding
};

} // namespace sph
