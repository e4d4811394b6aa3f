#pragma once
// All-pairs neighbour search, O(N^2): the reference the faster searches are
// tested against, and the seed report's starting point before hashing.

#include "sph/neighbours/neighbour_search.hpp"

namespace sph {

template <int D>
class AllPairs final : public NeighbourSearch<D> {
  public:
    std::string_view name() const override { return "all_pairs"; }
    void find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) override {
        const std::size_t n = positions.size();
        const Real r2 = radius * radius;
        out.start.assign(1, 0);
        out.index.clear();
        for (std::size_t i = 0; i < n; ++i) {
            for (std::size_t j = 0; j < n; ++j) {
                if (j != i && squared_length<D>(positions[i] - positions[j]) < r2)
                    out.index.push_back(static_cast<std::uint32_t>(j));
            }
            out.start.push_back(static_cast<std::uint32_t>(out.index.size()));
        }
        out.size_for(out.index.size());
    }
};

} // namespace sph
