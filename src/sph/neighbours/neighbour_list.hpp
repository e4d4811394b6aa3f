#pragma once
// Neighbour lists in compressed rows: the neighbours of particle i are
// index[start[i] .. start[i+1]). A particle is not listed among its own
// neighbours. Built once per step, read by every stage of that step.

#include <cstdint>
#include <span>
#include <vector>

namespace sph {

struct NeighbourList {
    std::vector<std::uint32_t> start; // size n + 1
    std::vector<std::uint32_t> index;

    std::span<const std::uint32_t> of(std::size_t i) const {
        return {index.data() + start[i], index.data() + start[i + 1]};
    }
    std::size_t particle_count() const { return start.empty() ? 0 : start.size() - 1; }
    std::size_t pair_count() const { return index.size(); }
};

} // namespace sph
