#include "parallel/world.hpp"

#include <cstdlib>

#ifdef SPHCLIP_HAVE_MPI
#include <mpi.h>
#endif

namespace sph::parallel {

namespace {

#ifdef SPHCLIP_HAVE_MPI
bool active = false;

// Set by the starters in every process they start: Open MPI's mpirun,
// PMIx and PMI-2 based ones (Slurm's srun, MPICH's Hydra).
bool launched_by_mpi_starter() {
    static constexpr const char* names[] = {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK",
                                            "PMI_SIZE"};
    for (const char* name : names)
        if (std::getenv(name))
            return true;
    return false;
}
#endif

} // namespace

Session::Session([[maybe_unused]] int* argc, [[maybe_unused]] char*** argv) {
#ifdef SPHCLIP_HAVE_MPI
    if (!launched_by_mpi_starter())
        return;
    int provided = 0;
    MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
    active = true;
#endif
}

Session::~Session() {
#ifdef SPHCLIP_HAVE_MPI
    if (active)
        MPI_Finalize();
    active = false;
#endif
}

bool built_with_mpi() {
#ifdef SPHCLIP_HAVE_MPI
    return true;
#else
    return false;
#endif
}

int rank() {
#ifdef SPHCLIP_HAVE_MPI
    if (active) {
        int r = 0;
        MPI_Comm_rank(MPI_COMM_WORLD, &r);
        return r;
    }
#endif
    return 0;
}

int size() {
#ifdef SPHCLIP_HAVE_MPI
    if (active) {
        int n = 1;
        MPI_Comm_size(MPI_COMM_WORLD, &n);
        return n;
    }
#endif
    return 1;
}

bool any_rank(bool flag) {
#ifdef SPHCLIP_HAVE_MPI
    if (active && size() > 1) {
        int mine = flag ? 1 : 0, any = 0;
        MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
        return any != 0;
    }
#endif
    return flag;
}

bool leader_says(bool flag) {
#ifdef SPHCLIP_HAVE_MPI
    if (active && size() > 1) {
        int value = flag ? 1 : 0;
        MPI_Bcast(&value, 1, MPI_INT, 0, MPI_COMM_WORLD);
        return value != 0;
    }
#endif
    return flag;
}

int end_job(int code) {
#ifdef SPHCLIP_HAVE_MPI
    if (active && size() > 1)
        MPI_Abort(MPI_COMM_WORLD, code);
#endif
    return code;
}

} // namespace sph::parallel
