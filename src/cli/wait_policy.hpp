#pragma once
// How sphclip's OpenMP threads wait, on a machine it may share (issue 22,
// item 4; docs/benchmarks.md, "Busy machines").
//
// libgomp reads its wait policy once, from the environment, before main()
// runs. Its default spins up to 300,000 times at every barrier before it
// sleeps. On a machine where another process holds a core, the spinning
// thread takes the core from the thread it waits for. The 5,000-particle
// dam break then ran at 0.07x of `--threads 1`. So when the user has set
// neither OMP_WAIT_POLICY nor GOMP_SPINCOUNT, sphclip runs with
// GOMP_SPINCOUNT = `default_spin_count`. A policy the user sets is kept.
//
// The launcher, `sphclip` itself (cli/launcher.c), sets it before the
// program proper starts. A program started some other way (its file under
// libexec/ named directly) sets it and starts itself again, once, with the
// same arguments, before anything else happens: that loads its 160 shared
// libraries a second time, 0.2 s here, which is why the launcher exists.
// Tried before it and dropped (2026-12-05): setting the variable from the
// program's .preinit_array (libc's initialiser, which runs after it, resets
// the environment) and from the initialiser of a small shared library of our
// own (the loader initialises libgomp early, as a dependency of libsoxr and
// others, before any library the program itself names). tests/
// test_run_json.cpp checks through libgomp's own report (OMP_DISPLAY_ENV)
// that the spin count is in force.

#include "cli/spin_count.h"

namespace sph {

// Spins before a waiting thread sleeps, chosen by sphclip_bench_flow on a
// quiet and a loaded machine (docs/benchmarks.md, "Busy machines").
inline constexpr const char* default_spin_count = SPHCLIP_DEFAULT_SPIN_COUNT;

// Returns when the policy is in force. Otherwise it re-executes the program
// and does not return. It also returns when /proc/self/exe cannot be
// executed; the run then keeps libgomp's default.
void apply_wait_policy(char** argv);

} // namespace sph
