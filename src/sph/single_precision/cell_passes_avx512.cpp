// The single-precision passes for x86-64-v4's AVX-512 (single_passes.hpp).
#include "sph/single_precision/single_passes.hpp"

#pragma GCC push_options
#pragma GCC target(                                                                                \
    "avx512f,avx512vl,avx512bw,avx512dq,avx512cd,avx2,fma,bmi,bmi2,lzcnt,movbe,f16c,prefer-vector-width=256")
#define SPHCLIP_SIMD_VARIANT avx512
#include "sph/single_precision/cell_passes.hpp"
#pragma GCC pop_options
