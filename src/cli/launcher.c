/* `sphclip` as users, scripts, mpirun and Slurm jobs call it: a front door
   that sets libgomp's spin count when the user set no wait policy
   (cli/wait_policy.hpp says why it must be set before libgomp starts), then
   starts the program proper in its place (same process, same arguments):
   ../libexec/sphclip/sphclip beside an installed launcher, libexec/sphclip/
   sphclip in a build folder (SPHCLIP_PROGRAM_* from CMake). It links libc
   alone, so its own start costs about a millisecond; the program, which
   before 2026-12-05 set the variable by starting itself again, loaded its
   160 shared libraries twice, 0.2 s on every start.
   SPHCLIP_LAUNCHER tells the program where its launcher is, so that it
   finds its data beside it and names it to the runs it starts
   (cli/child_process.cpp, self_executable). */
#include "cli/spin_count.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int main(int argc, char** argv) {
    (void)argc;
    char self[PATH_MAX];
    const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
    if (length <= 0) {
        fprintf(stderr, "sphclip: error: cannot read /proc/self/exe: %s\n", strerror(errno));
        return 1; /* exit_failure (cli/exit_codes.hpp) */
    }
    self[length] = '\0';
    if (!getenv("OMP_WAIT_POLICY") && !getenv("GOMP_SPINCOUNT"))
        setenv("GOMP_SPINCOUNT", SPHCLIP_DEFAULT_SPIN_COUNT, 1);
    setenv("SPHCLIP_LAUNCHER", self, 1);
    *strrchr(self, '/') = '\0'; /* the launcher's folder */
    static const char* const places[] = {SPHCLIP_PROGRAM_INSTALLED, SPHCLIP_PROGRAM_IN_BUILD};
    char program[2][PATH_MAX + 64];
    int failure[2];
    for (int k = 0; k < 2; ++k) {
        snprintf(program[k], sizeof program[k], "%s/%s", self, places[k]);
        execv(program[k], argv);
        failure[k] = errno; /* not found, or found and not runnable: say which */
    }
    fprintf(stderr,
            "sphclip: error: cannot start the program proper beside its launcher: %s: %s; %s: %s\n",
            program[0], strerror(failure[0]), program[1], strerror(failure[1]));
    return 1;
}
