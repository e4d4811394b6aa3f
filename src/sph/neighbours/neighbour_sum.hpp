#pragma once
// Sums over a particle's row of a neighbour list, in loops the compiler
// vectorises: an OpenMP `simd` reduction lets it keep one partial sum per
// vector lane, which a plain loop's fixed left-to-right order forbids. The
// order of the additions is then set by the row and the compiled vector
// width only, so a run still gives the same bits with any thread count
// (-fopt-info-vec lists these loops as vectorised; docs/benchmarks.md, "Which loops vectorise").
//
// The term is a Real or a Vec<D>; it must be a pure function of its
// arguments, without a branch that calls out of line (a select, `c ? a : b`,
// is fine), or the loop stays scalar.

#include "sph/neighbours/neighbour_list.hpp"
#include "sph/vec.hpp"
#include "sph/vector_clones.hpp"

#include <cstdint>
#include <type_traits>

// The loops' width in pairs, pinned to the row padding's (simd_lanes) in a
// build for one processor: left to itself, GCC 12 takes 16 pairs an
// iteration with AVX-512 (the 32-bit neighbour index fills a vector at 16,
// and the doubles take two), so a row padded to 8 whose length is not a
// multiple of 16 ended in 8 pairs of scalar code (measured on dfsph's 3D
// dam break, double: density 74 -> 54 ns a particle-step, viscosities 160
// -> 134). Not in a build with clones: there simd_lanes is the baseline's
// (2), and each clone keeps its own width.
#define SPHCLIP_PRAGMA(text) _Pragma(#text)
#if defined(SPHCLIP_VECTOR_CLONES_ON)
#define SPHCLIP_ROW_SIMD(...) SPHCLIP_PRAGMA(omp simd __VA_ARGS__)
#else
#define SPHCLIP_ROW_SIMD(...) SPHCLIP_PRAGMA(omp simd simdlen(simd_lanes) __VA_ARGS__)
#endif

namespace sph {

// sum over e in row i of term(e, index[e]); e (a std::size_t) is the pair's
// place in the list, for arrays kept per pair.
template <class Term>
SPHCLIP_INLINE_IN_CLONES auto sum_over_pairs(const NeighbourList& list, std::size_t i,
                                             Term&& term_argument) {
    // A local copy: loads of what the term captures, through the caller's
    // closure, are then seen not to change in the loop (otherwise GCC 12
    // gives up on it: "no vectype for stmt").
    const std::decay_t<Term> term = term_argument;
    using T = std::decay_t<decltype(term(std::size_t(0), std::uint32_t(0)))>;
    // 64-bit positions: a 32-bit one could wrap, so GCC would not see
    // consecutive e as consecutive addresses and would gather index[e].
    const std::size_t begin = list.start[i], end = list.start[i + 1];
    const std::uint32_t* index = list.index.data();
    // The loop runs a whole number of vectors: the lanes past the row's end
    // read the next rows or the list's padding (neighbour_list.hpp), and add
    // 0. A row of 20 would otherwise end in a scalar remainder of 4 that
    // costs as much as the 16 before it. Arrays kept per pair need the same
    // padding.
    const std::size_t padded_end = begin + (end - begin + simd_lanes - 1) / simd_lanes * simd_lanes;
    if constexpr (std::is_same_v<T, Real>) {
        Real s = 0;
        SPHCLIP_ROW_SIMD(reduction(+ : s))
        for (std::size_t e = begin; e < padded_end; ++e) {
            const Real t = term(e, index[e]);
            s += e < end ? t : 0;
        }
        return s;
    } else if constexpr (T::length() == 2) {
        Real x = 0, y = 0;
        SPHCLIP_ROW_SIMD(reduction(+ : x, y))
        for (std::size_t e = begin; e < padded_end; ++e) {
            const T t = term(e, index[e]);
            x += e < end ? t.x : 0;
            y += e < end ? t.y : 0;
        }
        return T(x, y);
    } else {
        static_assert(T::length() == 3, "a term is a Real, a Vec<2> or a Vec<3>");
        Real x = 0, y = 0, z = 0;
        SPHCLIP_ROW_SIMD(reduction(+ : x, y, z))
        for (std::size_t e = begin; e < padded_end; ++e) {
            const T t = term(e, index[e]);
            x += e < end ? t.x : 0;
            y += e < end ? t.y : 0;
            z += e < end ? t.z : 0;
        }
        return T(x, y, z);
    }
}

// sum over the neighbours j of particle i of term(j).
template <class Term>
SPHCLIP_INLINE_IN_CLONES auto sum_over_neighbours(const NeighbourList& list, std::size_t i,
                                                  const Term& term) {
    return sum_over_pairs(list, i, [term](std::size_t, std::uint32_t j) { return term(j); });
}

} // namespace sph
