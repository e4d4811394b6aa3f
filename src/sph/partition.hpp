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
    // `state`, the whole simulation's (the same on every process), becomes
    // this process's share.
    virtual void adopt(State<D>& state) = 0;
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
    // mark_buried (sph/surface.hpp) of every particle, after
    // update_fields(): each process marks its share from its lists
    // (`neighbours`, update_fields' context's) and every process gets all.
    virtual void mark_buried(const NeighbourList& neighbours, Real spacing,
                             std::vector<std::uint8_t>& buried) = 0;
    // The whole simulation's state, on every process, from each one's share.
    virtual void gather(const State<D>& share, State<D>& whole) = 0;
    // What run.json records: ranks, decomposition, balance, bytes moved.
    virtual nlohmann::json report() const = 0;
};

// Makes the partition of a simulation from its parameters and effects, or
// null (one process); Simulation calls it before anything else, so that no
// process ever works on the whole state.
template <int D>
using PartitionMaker =
    std::function<std::unique_ptr<Partition<D>>(const Params<D>&, const EffectList<D>&)>;

} // namespace sph
