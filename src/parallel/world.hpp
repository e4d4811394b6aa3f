#pragma once
// The MPI job this process belongs to (docs/mpi.md). A process that mpirun
// (or srun) started initialises MPI; one started any other way is a job of
// one rank and never touches MPI, so that a plain run costs nothing and
// starts no Open MPI runtime (a singleton MPI_Init forks one). Without MPI at
// build time (SPHCLIP_MPI=OFF) every process is a job of one rank.

namespace sph::parallel {

// Initialises MPI, when launched by an MPI starter, for the life of the
// object (MPI_THREAD_FUNNELED: only the main thread calls MPI; OpenMP
// threads and the encoder's worker never do). One per process, in main().
class Session {
  public:
    Session(int* argc, char*** argv);
    ~Session();
    Session(const Session&) = delete;
    Session& operator=(const Session&) = delete;
};

// Whether this build can run over MPI ranks.
bool built_with_mpi();
// This process's rank, and the number of ranks (1 without MPI).
int rank();
int size();
inline bool leader() {
    return rank() == 0;
}

// True on every rank when `flag` is true on any (an all-reduce): the ranks
// of one simulation decide together, between the same two steps, to stop.
// Just `flag` on one rank.
bool any_rank(bool flag);
// Rank 0's value of `flag`, on every rank.
bool leader_says(bool flag);
// Ends every rank of the job with `code` (MPI_Abort) when there is more
// than one; returns `code` otherwise. For a failure only some ranks see
// (an output rank 0 could not write): the others would wait forever in
// the next collective call.
int end_job(int code);

} // namespace sph::parallel
