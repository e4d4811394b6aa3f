/* libgomp's spin count sphclip runs with when the user set no wait policy
   (cli/wait_policy.hpp says why; docs/benchmarks.md, "Busy machines"):
   one value for the launcher (C) and the program (C++). */
#pragma once
#define SPHCLIP_DEFAULT_SPIN_COUNT "10000"
