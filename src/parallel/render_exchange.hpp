#pragma once
// The ranks' side of depth compositing (render/depth_composite.hpp,
// docs/mpi.md "Rendering over ranks"), over MPI: the shadow map's minimum
// (MPI_Allreduce), the frame's counts (MPI_Reduce), and each rank's layer
// sent to rank 0 (MPI_Isend, which the next frame waits for; rank 0 posts
// MPI_Irecv for every rank and takes the layers as they arrive), on a
// communicator of its own.

#include "render/rank_compositing.hpp"

#include <cstddef>
#include <memory>

namespace sph::parallel {

// The job's ranks composite a frame by depth when it has at least
// `from_particles` particles (0: always), else draw it whole on rank 0.
// Null on one rank or without MPI. Every rank makes it (a collective call).
#ifdef SPHCLIP_HAVE_MPI
std::unique_ptr<RankCompositing> make_render_exchange(std::size_t from_particles);
#else
inline std::unique_ptr<RankCompositing> make_render_exchange(std::size_t) {
    return nullptr; // a build without MPI: every process is a job of one rank
}
#endif

} // namespace sph::parallel
