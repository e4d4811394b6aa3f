#pragma once
// One simulation over MPI ranks (docs/mpi.md): the steps of every solver
// (seed, wcsph, dfsph) shared out along the sorted grid's cell order.
//
// Each rank holds a contiguous range of the particles in the one-process
// memory order (its share), and only those between frames. The ranges are
// cut by count at every spatial sort, which the ranks make together (each
// particle goes to the place a one-process stable sort by cell key gives
// it, and to the rank that owns that place: migration), and when they grow
// uneven (params.rebalance_above). A step runs the solver on the share plus
// a halo, the other ranks' particles within K support radii plus the
// distance a step can move them, in the global memory order: each rank
// sends the ranks whose boxes meet its own its occupied coarse cells, gets
// back their particles beside them (candidates), keeps those near its own
// and tells their owners which. After the density stage the halo's
// densities and pressures are those their owners computed, sent point to
// point (MPI_Isend/Irecv, StepContext's HaloExchange), so K counts the
// neighbour sums after it: 1 (the forces), or 2 with surface tension.
// dfsph's solves exchange the halo's stiffnesses and velocities the same
// way in every iteration, and sum their errors in particle order across
// the ranks. A frame's fields are computed the same way, then the whole
// state is gathered on every rank for the frame's outputs.
//
// Same bits on any number of ranks: an owned particle's neighbour rows
// list the same neighbours in the same (memory) order as on one rank, so
// every neighbour sum adds the same terms in the same order
// (sph/neighbours/neighbour_sum.hpp); the halo's values are replaced by
// their owners' (complete, so the one-process bits) before a sum reads
// them, and the halo's other results, from incomplete neighbourhoods, are
// never kept. What a step reduces over all particles is a maximum or a
// flag (the adaptive dt, the watchdog: exact in any order), or a sum taken
// on the gathered whole state (the frame statistics); dfsph's sums within
// a step are added one particle after the other in memory order, each rank
// continuing the sum of the ranks before it: no reduction depends on the
// rank count.

#include "sph/partition.hpp"

#include <memory>
#include <string>

namespace sph::parallel {

// A partition over this job's ranks; null when there is one rank (or no
// MPI). Throws InputError (naming `scene_file`) for what cannot run over
// ranks yet: solver.precision single with reflecting walls.
#ifdef SPHCLIP_HAVE_MPI
template <int D>
std::unique_ptr<Partition<D>> make_rank_partition(const Params<D>& params,
                                                  const EffectList<D>& effects,
                                                  const std::string& scene_file);
#else
template <int D>
std::unique_ptr<Partition<D>> make_rank_partition(const Params<D>&, const EffectList<D>&,
                                                  const std::string&) {
    return nullptr; // a build without MPI: every process is a job of one rank
}
#endif

} // namespace sph::parallel
