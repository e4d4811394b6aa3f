#pragma once
// The interface every solver implements. A solver's step() reads like its
// algorithm: a named call per stage, the stages themselves in their own files.

#include "sph/boundaries/boundary.hpp"
#include "sph/effects/effect.hpp"
#include "sph/effects/viscosity_keys.hpp"
#include "sph/neighbours/neighbour_search.hpp"
#include "sph/stage_times.hpp"
#include "sph/time_step.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// Over MPI ranks (src/parallel/, docs/mpi.md) a step holds its rank's own
// particles, a run of its local state in the global memory order, and a halo
// around them. After the density stage the halo's densities and pressures
// are replaced by those their owners computed, from complete
// neighbourhoods: the sums that follow then need a halo one support radius
// wide, not one per neighbour sum of the step. An iterative solve (dfsph)
// does the same with the values each iteration's sums read, and continues
// its sums over all particles from rank to rank.
template <int D>
class HaloExchange {
  public:
    virtual ~HaloExchange() = default;
    virtual void share_densities(State<D>& state) = 0;
    // The halo's entries of a per-particle array from their owners.
    virtual void share(std::span<Real> values) = 0;
    virtual void share(std::span<Vec<D>> values) = 0;
    // The owned particles: [begin, end) of the local state.
    virtual std::size_t owned_begin() const = 0;
    virtual std::size_t owned_end() const = 0;
    // Particles over all ranks.
    virtual std::size_t total_particles() const = 0;
    // A sum in particle order over all ranks: what the ranks before this
    // one summed (0 on the first), then, given this rank's continuation of
    // it, the whole sum, on every rank.
    virtual Real sum_before() = 0;
    virtual Real finish_sum(Real sum) = 0;
    // The largest of every rank's `value` (exact in any order).
    virtual Real max_over_ranks(Real value) = 0;
    // Empties the halo's rows of a neighbour list just built, where no
    // result of the step read from a halo particle's own neighbours is kept
    // or read by an owned one (the halo's densities come from their owners;
    // its forces are discarded): the passes then skip the halo's rows.
    virtual void trim_rows(NeighbourList& /*list*/) const {}
    // Tells the search which rows trim_rows() would keep, so that it need
    // not list the others.
    virtual void want_rows(NeighbourSearch<D>& /*search*/) const {}
};

// What a step needs besides parameters and state: the neighbour search and the
// lists it fills (reused every step), the boundary particles when there are
// any, the scene's effects and its boundaries.
template <int D>
struct StepContext {
    NeighbourSearch<D>& search;
    NeighbourList& neighbours;
    const BoundaryParticles<D>* boundary; // null: walls reflect (the seed's)
    NeighbourList& boundary_neighbours;   // fluid -> boundary particles
    const EffectList<D>& effects;
    const BoundaryList<D>& boundaries; // walls, obstacles, paddles (boundary_set.hpp)
    StageTimes* stages = nullptr;      // where stage times go; null: not timed
    Real dt = 0;                       // s, the step being taken (XSPH reads it)
    Real start_time = 0;               // s, when the step starts (paddles move with it)
    bool output_pressure = true;       // an output reads the pressure field (FrameFields)
    // The boundary set again, writable, when it holds paddles; null when
    // nothing in it moves.
    BoundaryParticles<D>* moving_boundary = nullptr;
    // The ranks' halo exchange; null in one process.
    HaloExchange<D>* halo = nullptr;

    // How many times this step has been halved: a step the solver asks to
    // redo (StepReport::redo_in_halves) is taken again as two halves.
    int halvings = 0;

    // The halo particles' densities and pressures from the ranks that own
    // them (HaloExchange); nothing in one process. After the density stage.
    void share_halo_densities(State<D>& state) {
        if (!halo)
            return;
        auto timed = time(Stage::halo_exchange);
        halo->share_densities(state);
    }
    // The halo's entries of `values` from their owners; nothing in one
    // process. Untimed: an iterative solve calls it inside its own stage.
    template <class T>
    void share_halo(std::vector<T>& values) {
        if (halo)
            halo->share(std::span<T>(values));
    }
    // Particles in the whole simulation: n, the state's, in one process.
    std::size_t total_particles(std::size_t n) const { return halo ? halo->total_particles() : n; }
    // sum_i term(i) over the whole simulation's particles, added one by one
    // in particle (memory) order, as one process adds them: over ranks each
    // rank adds its owned run to what the ranks before it summed, so the
    // bits, and every decision taken on the sum, are the same on any number
    // of ranks (an MPI_Allreduce would add the ranks' partial sums, whose
    // bits depend on where the ranges are cut). n: the state's particles.
    template <class Term>
    Real sum_in_particle_order(std::size_t n, Term term) {
        if (!halo) {
            Real sum = 0;
            for (std::size_t i = 0; i < n; ++i)
                sum += term(i);
            return sum;
        }
        Real sum = halo->sum_before();
        for (std::size_t i = halo->owned_begin(); i < halo->owned_end(); ++i)
            sum += term(i);
        return halo->finish_sum(sum);
    }

    // Moves the boundary particles that move (the paddles') to where their
    // motions have them at time t, with their velocities.
    void place_boundaries(Real t) {
        if (!moving_boundary)
            return;
        for (const auto& b : boundaries)
            if (b->moves()) {
                auto timed = time(StageName::of(*b));
                b->place(t, *moving_boundary);
            }
    }

    // The last guard, at the end of a step that ends at time t: what the
    // boundaries put back (boundary.hpp), each timed under its own name; the
    // pushes stats.csv counts.
    std::uint64_t last_guard(Real t, State<D>& state) {
        return sph::last_guard<D>(boundaries, t, state, stages);
    }

    // Times the stage that lives as long as the returned scope.
    StageTimes::Scope time(StageName stage) { return {stages, stage}; }

    // Fills both lists for the current positions.
    void find_neighbours(std::span<const Vec<D>> positions, Real h) {
        {
            auto timed = time(Stage::neighbour_search);
            if (halo)
                halo->want_rows(search);
            search.find(positions, h, neighbours);
            if (halo) {
                halo->trim_rows(neighbours);
                search.want_rows(0, ~std::size_t(0));
            }
        }
        if (boundary) {
            auto timed = time(Stage::boundary_neighbours);
            boundary->find_neighbours(positions, boundary_neighbours);
            if (halo)
                halo->trim_rows(boundary_neighbours);
        }
    }

    // Adds every effect's acceleration, each timed under its own name, but
    // those in `merged`, which the solver added in a pass of its own, the
    // stage `merged_into`: the stage table lists them as done there.
    void apply_effects(const Params<D>& params, State<D>& state,
                       std::span<const Effect<D>* const> merged = {},
                       Stage merged_into = Stage::pressure) {
        for (const auto& effect : effects) {
            if (std::find(merged.begin(), merged.end(), effect.get()) != merged.end()) {
                if (stages)
                    stages->add_within(StageName::of(*effect), merged_into);
                continue;
            }
            auto timed = time(StageName::of(*effect));
            effect->apply(params, {neighbours, boundary, boundary_neighbours, dt}, state);
        }
    }
};

// What one step did, for stats.csv.
struct StepReport {
    int pressure_iterations = 0;       // dfsph: density solve
    int divergence_iterations = 0;     // dfsph: divergence solve
    std::uint64_t obstacle_pushes = 0; // particles put back out of an obstacle (obstacles.hpp)
    // The step did not hold (dfsph: its density solve ended above its
    // tolerance): the state is as it started but for fields the step
    // recomputes, and the caller takes it again as two halves.
    bool redo_in_halves = false;
};

template <int D>
class Solver {
  public:
    virtual ~Solver() = default;
    virtual std::string_view name() const = 0;
    virtual TimeStepModel time_step_model() const = 0;
    // Advances the state by dt.
    virtual StepReport step(const Params<D>& params, Real dt, State<D>& state,
                            StepContext<D>& context) = 0;
    // Density and pressure at the current positions, as the next step would
    // compute them; used for the frame outputs. Moves nothing.
    virtual void update_fields(const Params<D>& params, State<D>& state,
                               StepContext<D>& context) = 0;
    // Energy per unit mass, J/kg, that the solver's equation of state stores
    // in fluid at density rho: what a compressed start releases as motion.
    // None for an incompressible solver.
    virtual Real compression_energy(const Params<D>& /*params*/, Real /*rho*/) const { return 0; }
    // The particle arrays were reordered between steps (State::permute with
    // `order`): per-particle arrays kept from one step to the next must
    // follow. Nothing to do for a solver that keeps none.
    virtual void permute(std::span<const std::uint32_t> /*order*/) {}
    // Those per-particle arrays, each empty or sized to the state the last
    // step was given. Over MPI ranks the partition keeps them for its own
    // particles (they migrate with them): before a step it gives the solver
    // the entries of the particles the step holds (the halo's from their
    // owners), after it keeps the owned ones (docs/mpi.md).
    virtual std::span<std::vector<Real>* const> kept_arrays() { return {}; }
    // The state's arrays a step reads as the last step left them (besides
    // positions, velocities and ids): what the watchdog saves for a retry.
    // All of them unless the solver knows better.
    virtual StepInputs step_inputs(const Params<D>& /*params*/) const { return {}; }
};

// What a solver can do and what it chooses when the scene says "auto",
// declared in its own file; the scene's checks and defaults ask these
// rather than the solver's name.
struct SolverCapabilities {
    std::string_view name; // solver.name
    SolverKind kind = SolverKind::seed;
    bool carries_sound = true;     // weakly compressible: the step is bounded by the sound speed
    bool wall_particles = true;    // boundary particles: walls, obstacles, paddles
    bool supports_verlet = true;   // solver.integrator verlet
    bool single_precision = false; // float passes over grid cells (solver.precision single)
    KernelKind default_kernel = KernelKind::cubic_spline; // solver.kernel auto
    // solver.artificial_viscosity applies without an effects.artificial_viscosity key.
    bool default_artificial_viscosity = false;
    ViscosityModel viscosity_model = ViscosityModel::morris; // effects.viscosity's default model
    // solver.reorder_every without the key (chosen on the flows: docs/benchmarks.md,
    // "The pairs in slices").
    int reorder_every = 20;
};

// Names accepted by make_solver (`solver.name`), in the order docs/scene-keys.md lists them.
std::vector<std::string> solver_names();
const SolverCapabilities& solver_capabilities(SolverKind kind);

template <int D>
std::unique_ptr<Solver<D>> make_solver(SolverKind kind, const Params<D>& params);

} // namespace sph
