#pragma once
// Neighbour lists in compressed rows: the neighbours of particle i are
// index[start[i] .. start[i+1]). A particle is not listed among its own
// neighbours. Built once per step, read by every stage of that step.
//
// After the last row, `index` holds simd_lanes zeros (particle 0): a vector
// loop over a row may then read whole vectors past the row's end, and
// discard those lanes, instead of finishing in a scalar remainder
// (sph/neighbours/neighbour_sum.hpp).

#include "sph/headroom.hpp"

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace sph {

// Doubles in one vector register of the target: the force loops' width.
#if defined(__AVX512F__)
inline constexpr std::uint32_t simd_lanes = 8;
#elif defined(__AVX__)
inline constexpr std::uint32_t simd_lanes = 4;
#else
inline constexpr std::uint32_t simd_lanes = 2;
#endif

struct NeighbourList {
    std::vector<std::uint32_t> start; // size n + 1
    std::vector<std::uint32_t> index; // pair_count() entries, then the padding

    std::span<const std::uint32_t> of(std::size_t i) const {
        return {index.data() + start[i], index.data() + start[i + 1]};
    }
    std::size_t particle_count() const { return start.empty() ? 0 : start.size() - 1; }
    std::size_t pair_count() const { return start.empty() ? 0 : start.back(); }

    // Sizes `index` for `pairs` entries and the padding after them (zeros),
    // with the headroom that keeps a step from allocating (sph/headroom.hpp).
    // Call it before writing the rows, or after: it keeps the first `pairs`.
    void size_for(std::size_t pairs) {
        resize_with_headroom(index, pairs + simd_lanes);
        std::fill(index.begin() + static_cast<std::ptrdiff_t>(pairs), index.end(), 0u);
    }
};

} // namespace sph
