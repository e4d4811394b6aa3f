#pragma once
// The double-precision neighbour passes in several instruction sets, one
// picked when the program loads (GCC's target_clones: an ifunc resolver reads
// the processor's features once). For a portable x86-64 build
// (SPHCLIP_SIMD_DISPATCH, src/CMakeLists.txt): its baseline, x86-64-v2, has
// SSE's two doubles a vector and no gathers, and the passes ran at 0.77-0.9x
// of a native build's (docs/benchmarks.md, "Single precision on each
// processor"). A native build is compiled for its own processor and needs
// none. The float passes are dispatched by hand instead
// (sph/single_precision/single_passes.hpp), to pin one with SPHCLIP_SIMD.
//
// A clone covers the function's OpenMP regions (GCC outlines them first and
// clones the outlined bodies with it) and everything inlined into it, but not
// a lambda's own regions: a region must sit in the cloned function itself.

#if defined(SPHCLIP_VECTOR_CLONES) && defined(__x86_64__) && defined(__GNUC__) &&                  \
    !defined(__clang__)
#define SPHCLIP_VECTOR_CLONES_ON 1
#define SPHCLIP_CLONED __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
// For the helpers the clones' loops call (a row's sum): GCC would not inline
// them into a clone by itself, and their loops then ran at the baseline's
// width. Only in a build with clones: elsewhere it would move a native
// build's bits.
#define SPHCLIP_INLINE_IN_CLONES [[gnu::always_inline]] inline
#else
#define SPHCLIP_CLONED
#define SPHCLIP_INLINE_IN_CLONES
#endif

namespace sph {

// The instruction set the cloned passes run on this processor, as their
// resolvers choose it: "x86-64-v4" (AVX-512), "x86-64-v3" (AVX2, FMA),
// "baseline" (the build's -march, also a portable build by clang, which
// gets no clones), or "native" (a build for its own processor).
const char* vector_clone_variant();

} // namespace sph
