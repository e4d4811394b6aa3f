#include "cli/wait_policy.hpp"

#include <cstdlib>
#include <unistd.h>

namespace sph {

void apply_wait_policy(char** argv) {
    if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT"))
        return;
    if (setenv("GOMP_SPINCOUNT", default_spin_count, 1) != 0)
        return;
    // The same program, arguments and environment; the pid is kept, so a
    // parent (a shell, mpirun, Slurm, study's child pool) sees no change.
    execv("/proc/self/exe", argv);
    // Not reached unless exec failed (no /proc): run as libgomp starts.
    unsetenv("GOMP_SPINCOUNT");
}

} // namespace sph
