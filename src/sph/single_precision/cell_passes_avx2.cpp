// The single-precision passes for x86-64-v3's AVX2 and FMA (single_passes.hpp).
#include "sph/single_precision/single_passes.hpp"

#pragma GCC push_options
#pragma GCC target("avx2,fma,bmi,bmi2,lzcnt,movbe,f16c")
#define SPHCLIP_SIMD_VARIANT avx2
#define SPHCLIP_SIMD_BITS 256
#include "sph/single_precision/cell_passes.hpp"
#pragma GCC pop_options
