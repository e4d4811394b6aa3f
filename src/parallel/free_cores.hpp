#pragma once
// How many of the machine's cores other processes leave free now, from the
// kernel's count of runnable threads (the fourth field of /proc/loadavg),
// for the thread-count tuner (issue 22, item 4; docs/benchmarks.md, "Busy
// machines").
//
// The tuner finds a busy machine by stepping with more threads and losing:
// with one busy process on 2 cores each such try runs at 0.3x, and the tries
// cost the default 2-3% against --threads 1. Asking the kernel first costs
// a read of a small file. The count is the whole machine's, so it answers
// only where the process may run on every online CPU and no CPU quota
// applies (a cpuset or a quota makes other tasks' cores not ours to count);
// elsewhere the tuner measures, as before.

#include <functional>

namespace sph::parallel {

// free(own): the cores that no thread but our `own` running ones occupies,
// or -1 where this cannot be known.
using FreeCores = std::function<int(int own)>;

// The probe for this machine; an empty function where the kernel's count
// does not describe the cores this process runs on.
FreeCores free_cores_of_this_machine();

// The least of a few samples of /proc/loadavg's runnable count, 1 ms apart:
// a thread woken for a moment (a kernel worker, our own encoder) does not
// count as a busy core. -1 where the file cannot be read.
int runnable_threads();

} // namespace sph::parallel
