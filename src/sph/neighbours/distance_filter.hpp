#pragma once
// The distance filter of the neighbour searches: squared distances from a
// point to a run of candidates stored by component, then the candidates
// closer than the radius written out without a branch. The fluid's search
// (sorted_grid.cpp) and the walls' (boundaries/boundary_particles.cpp) share it.

#include "sph/vec.hpp"
#include "sph/vector_clones.hpp"

#include <bit>
#include <cstddef>
#include <cstdint>
#if (defined(__AVX512F__) && defined(__AVX512VL__)) || defined(SPHCLIP_VECTOR_CLONES_ON)
#include <immintrin.h>
#endif

namespace sph {

// Squared distances from p to the gathered candidates, summed in the order
// glm::dot sums, so a pair is in or out exactly as in AllPairs. Separate
// arrays and no aliasing: the loop vectorises.
inline void squared_distances(std::size_t count, const Real* __restrict x, const Real* __restrict y,
                              Real px, Real py, Real* __restrict out) {
    for (std::size_t m = 0; m < count; ++m) {
        const Real dx = x[m] - px, dy = y[m] - py;
        out[m] = dx * dx + dy * dy;
    }
}

inline void squared_distances(std::size_t count, const Real* __restrict x, const Real* __restrict y,
                              const Real* __restrict z, Real px, Real py, Real pz,
                              Real* __restrict out) {
    for (std::size_t m = 0; m < count; ++m) {
        const Real dx = x[m] - px, dy = y[m] - py, dz = z[m] - pz;
        out[m] = dx * dx + dy * dy + dz * dz;
    }
}

// The AVX-512 stream compaction of select_neighbours (below): compiled for
// the build's own processor in a native build for one with AVX-512, and with
// a target attribute in a build with clones (sph/vector_clones.hpp), where
// it runs when the processor has AVX-512 (a clone cannot test which clone
// it is: a preprocessor test sees the baseline).
#if defined(__AVX512F__) && defined(__AVX512VL__)
#define SPHCLIP_COMPRESS 1
#define SPHCLIP_COMPRESS_TARGET
inline bool compress_runs() {
    return true;
}
#elif defined(SPHCLIP_VECTOR_CLONES_ON)
#define SPHCLIP_COMPRESS 1
#define SPHCLIP_COMPRESS_TARGET __attribute__((target("avx512f,avx512vl,popcnt")))
inline bool compress_runs() {
    static const bool runs = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
    }();
    return runs;
}
#endif

#ifdef SPHCLIP_COMPRESS
// Eight candidates at a time: compare, compress the kept indices to the front
// of a register, store all eight and advance by the number kept (GCC does not
// vectorise this "stream compaction" by itself; it was 3/4 of the listing's
// time). Stored from a register: a compressing store to memory is microcoded
// on AMD Zen 4. The eight stored never pass row[m + 8], within the row's room
// since found <= m. Returns how many candidates it went through.
SPHCLIP_COMPRESS_TARGET inline std::size_t
compress_close(std::size_t count, const Real* __restrict distance2,
               const std::uint32_t* __restrict index, Real r2, std::uint32_t self,
               std::uint32_t* __restrict row, std::uint32_t& found) {
    const __m512d limit = _mm512_set1_pd(r2);
    const __m256i me = _mm256_set1_epi32(static_cast<int>(self));
    std::size_t m = 0;
    for (; m + 8 <= count; m += 8) {
        const __mmask8 close =
            _mm512_cmp_pd_mask(_mm512_loadu_pd(distance2 + m), limit, _CMP_LT_OQ);
        const __m256i candidates = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(index + m));
        const __mmask8 keep = close & _mm256_cmpneq_epi32_mask(candidates, me);
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(row + found),
                            _mm256_maskz_compress_epi32(keep, candidates));
        found += static_cast<std::uint32_t>(std::popcount(static_cast<unsigned>(keep)));
    }
    return m;
}
#endif

// The candidates closer than r2, other than `self`, written without a branch
// (a neighbour is ~1 candidate in 8, a branch on it mispredicts). `row` has
// room for `count` entries.
inline std::uint32_t select_neighbours(std::size_t count, const Real* __restrict distance2,
                                       const std::uint32_t* __restrict index, Real r2,
                                       std::uint32_t self, std::uint32_t* __restrict row) {
    std::uint32_t found = 0;
    std::size_t m = 0;
#ifdef SPHCLIP_COMPRESS
    if (compress_runs())
        m = compress_close(count, distance2, index, r2, self, row, found);
#endif
    for (; m < count; ++m) {
        row[found] = index[m];
        found += (distance2[m] < r2) & (index[m] != self);
    }
    return found;
}

} // namespace sph
