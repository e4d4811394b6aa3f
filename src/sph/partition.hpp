#pragma once
// How one step is shared out when a simulation runs over several processes
// (src/parallel/, docs/mpi.md). Simulation hands each step to its partition,
// when it has one, instead of calling the solver itself; the partition runs
// the solver on this process's share and leaves `state` as the whole step
// would have left it. Nothing here knows about MPI.

#include "sph/solvers/solver.hpp"

#include <nlohmann/json.hpp>

namespace sph {

template <int D>
class Partition {
  public:
    virtual ~Partition() = default;
    // solver.step(params, dt, state, context), shared out; the same bits in
    // `state` as that call would give.
    virtual StepReport step(Solver<D>& solver, const Params<D>& params, Real dt, State<D>& state,
                            StepContext<D>& context) = 0;
    // The particle arrays were reordered between steps (State::permute
    // with `order`): what the partition keeps per particle follows.
    virtual void permute(std::span<const std::uint32_t> /*order*/) {}
    // What run.json records: ranks, decomposition, balance, bytes moved.
    virtual nlohmann::json report() const = 0;
};

} // namespace sph
