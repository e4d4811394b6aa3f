// The single-precision passes for the build's own -march: every processor
// the binary runs on (single_passes.hpp). In a build for the build machine's
// processor (SPHCLIP_ARCH=native) this is the only variant, "native".
#include "sph/single_precision/single_passes.hpp"

#define SPHCLIP_SIMD_VARIANT baseline
#include "sph/single_precision/cell_passes.hpp"
