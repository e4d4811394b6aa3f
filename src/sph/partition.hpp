#pragma once
// How a simulation is shared out when it runs over several processes
// (src/parallel/, docs/mpi.md). Each process holds a contiguous run of the
// particles in memory order (rank 0 the first): Simulation's state is that
// run, and Simulation hands each step, each spatial sort and each frame's
// fields to its partition, when it has one, instead of doing them itself.
// The results are the same bits as one process's. Nothing here knows about
// MPI.

#include "sph/collective.hpp"
#include "sph/solvers/solver.hpp"

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>

namespace sph {

template <int D>
class Partition : public Collective {
  public:
    // Where this process starts: the run [first, first + count) of the
    // initial state's `total` particles (in make_initial_state's order),
    // so that no process builds the whole initial state.
    struct Share {
        std::size_t first = 0, count = 0;
    };
    virtual Share starting_share(std::size_t total) = 0;
    // `share`, the particles of starting_share(), is this process's.
    virtual void adopt(State<D>& share) = 0;
    // solver.step(params, dt, state, context) on the whole simulation, each
    // process stepping its share: `state` (the share) as that call would
    // have left it.
    virtual StepReport step(Solver<D>& solver, const Params<D>& params, Real dt, State<D>& state,
                            StepContext<D>& context) = 0;
    // The spatial sort (SortedGrid::cell_order with radius h) of the whole
    // simulation's particles, then the ranges cut again by count: particles
    // move to the process that owns their new place.
    virtual void reorder(State<D>& state, Real h) = 0;
    // The ranges cut again by count when they have grown uneven (particles
    // added; params.rebalance_above).
    virtual void rebalance(State<D>& state) = 0;
    // solver.update_fields(params, state, context) on the whole simulation,
    // each process computing its share's fields (with a halo); the
    // context's neighbour lists are then this process's step particles'.
    virtual void update_fields(Solver<D>& solver, const Params<D>& params, State<D>& state,
                               StepContext<D>& context) = 0;
    // mark_buried (sph/surface.hpp), after update_fields(): each process
    // marks its share from its lists (`neighbours`, update_fields'
    // context's); `buried` is then every particle's on process 0 (which
    // draws) and the share's on the others. Every process calls it.
    virtual void mark_buried(const NeighbourList& neighbours, Real spacing,
                             std::vector<std::uint8_t>& buried) = 0;
    // The whole simulation's state into `whole` on process 0, from each
    // one's share (the others' `whole` is left as it is). Every process
    // calls it.
    virtual void gather(const State<D>& share, State<D>& whole) = 0;
    // The wall particles (and obstacles' shells) each process holds are
    // those near its particles: after each exchange of the halo the
    // partition calls `cover` with the box holding every point where the
    // step may look for boundary particles, and Simulation lays the
    // boundary particles of a box around it when those it holds do not;
    // `cover` returns how many static ones it holds.
    using WallCover = std::function<std::size_t(const Box<D>&)>;
    virtual void cover_walls_with(WallCover cover) = 0;
    // What run.json records: ranks, decomposition, balance, bytes moved.
    virtual nlohmann::json report() const = 0;
};

// Makes the partition of a simulation from its parameters and effects, or
// null (one process); make_simulation calls it before it builds the
// initial state, so that no process ever holds the whole state.
template <int D>
using PartitionMaker =
    std::function<std::unique_ptr<Partition<D>>(const Params<D>&, const EffectList<D>&)>;

} // namespace sph
