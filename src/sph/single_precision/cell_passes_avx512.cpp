// The single-precision passes for x86-64-v4's AVX-512 (single_passes.hpp).
#include "sph/single_precision/single_passes.hpp"

// At 256-bit vectors, with AVX-512's masks and registers: on the AMD EPYC
// (Zen 4) measured the 2D flows' single step 1.33x faster than at 512 bits
// (8.3 against 6.2 M particle-steps/s, 2 threads) and 3D's 0.94x; 2D is
// where single precision is the default (docs/benchmarks.md).
#pragma GCC push_options
#pragma GCC target(                                                                                \
    "avx512f,avx512vl,avx512bw,avx512dq,avx512cd,avx2,fma,bmi,bmi2,lzcnt,movbe,f16c,prefer-vector-width=256")
#define SPHCLIP_SIMD_VARIANT avx512
#define SPHCLIP_SIMD_BITS 512
#include "sph/single_precision/cell_passes.hpp"
#pragma GCC pop_options
