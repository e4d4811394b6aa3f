#pragma once
// One simulation over MPI ranks (docs/mpi.md): the steps of every solver
// (seed, wcsph, dfsph) shared out along the sorted grid's cell order.
//
// Every rank keeps the whole particle state, in the same memory order; the
// simulation reorders it by cell every solver.reorder_every steps
// (simulation.cpp), identically on every rank. Rank r owns the particles at
// memory positions [N r / P, N (r + 1) / P): a contiguous range of the
// Morton curve, re-cut by particle count every step (re-cutting moves no
// data, every rank holding every particle). A step runs the solver on the
// owned particles plus a halo, the particles within K support radii plus
// the distance a step can move them, kept in the global memory order.
// After the density stage the halo's densities and pressures are those their
// owners computed, sent point to point (MPI_Isend/Irecv, StepContext's
// HaloExchange), so K counts the neighbour sums after it: 1 (the forces), or
// 2 with surface tension (normals, then forces from normals). dfsph's
// solves exchange the halo's stiffnesses and velocities the same way in
// every iteration, and sum their errors in particle order across the
// ranks. The owned particles' results, and the solver's arrays kept from
// step to step (dfsph's warm start), are then all-gathered (non-blocking
// MPI_Iallgatherv) into every rank's state.
//
// Same bits on any number of ranks: an owned particle's neighbour rows list
// the same neighbours in the same (memory) order as on one rank, so every
// neighbour sum adds the same terms in the same order
// (sph/neighbours/neighbour_sum.hpp); the halo's values are replaced by
// their owners' (complete, so the one-process bits) before a sum reads them,
// and the halo's other results, from incomplete neighbourhoods, are never
// kept. Whatever a step reduces over all particles (the adaptive dt, the
// watchdog, the frame statistics) is reduced over the gathered whole state,
// the same array in the same order on every rank; dfsph's sums within a
// step are added one particle after the other in memory order, each rank
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
