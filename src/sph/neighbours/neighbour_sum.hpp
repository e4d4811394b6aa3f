#pragma once
// Sums over a particle's row of a neighbour list, in loops the compiler
// vectorises: an OpenMP `simd` reduction lets it keep one partial sum per
// vector lane, which a plain loop's fixed left-to-right order forbids. The
// order of the additions is then set by the row and the compiled vector
// width only, so a run still gives the same bits with any thread count
// (-fopt-info-vec lists these loops as vectorised; README "Full step").
//
// The term is a Real or a Vec<D>; it must be a pure function of its
// arguments, without a branch that calls out of line (a select, `c ? a : b`,
// is fine), or the loop stays scalar.

#include "sph/neighbours/neighbour_list.hpp"
#include "sph/vec.hpp"

#include <cstdint>
#include <type_traits>

namespace sph {

// sum over e in row i of term(e, index[e]); e is the pair's place in the list,
// for arrays kept per pair.
template <class Term>
auto sum_over_pairs(const NeighbourList& list, std::size_t i, Term&& term) {
    using T = std::decay_t<decltype(term(std::uint32_t(0), std::uint32_t(0)))>;
    const std::uint32_t begin = list.start[i], end = list.start[i + 1];
    const std::uint32_t* index = list.index.data();
    if constexpr (std::is_same_v<T, Real>) {
        Real s = 0;
#pragma omp simd reduction(+ : s)
        for (std::uint32_t e = begin; e < end; ++e)
            s += term(e, index[e]);
        return s;
    } else if constexpr (T::length() == 2) {
        Real x = 0, y = 0;
#pragma omp simd reduction(+ : x, y)
        for (std::uint32_t e = begin; e < end; ++e) {
            const T t = term(e, index[e]);
            x += t.x;
            y += t.y;
        }
        return T(x, y);
    } else {
        static_assert(T::length() == 3, "a term is a Real, a Vec<2> or a Vec<3>");
        Real x = 0, y = 0, z = 0;
#pragma omp simd reduction(+ : x, y, z)
        for (std::uint32_t e = begin; e < end; ++e) {
            const T t = term(e, index[e]);
            x += t.x;
            y += t.y;
            z += t.z;
        }
        return T(x, y, z);
    }
}

// sum over the neighbours j of particle i of term(j).
template <class Term>
auto sum_over_neighbours(const NeighbourList& list, std::size_t i, Term&& term) {
    return sum_over_pairs(list, i, [&](std::uint32_t, std::uint32_t j) { return term(j); });
}

} // namespace sph
