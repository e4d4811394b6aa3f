#pragma once
// The seed's neighbour search ("spatial hashing", see ../shared/seed/MODEL.md):
// cells of size h, cell -> hash -> key = hash mod N, a lookup of
// (key, particle) pairs sorted by key, and the start of each key's run.
// Hash function: Teschner et al. 2003, "Optimized Spatial Hashing for Collision
// Detection of Deformable Objects", with wrap-around unsigned arithmetic so
// negative cell coordinates hash correctly.

#include "sph/neighbours/neighbour_search.hpp"

#include <utility>

namespace sph {

template <int D>
class SpatialHash final : public NeighbourSearch<D> {
  public:
    std::string_view name() const override { return "hash"; }
    void find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) override;

  private:
    using Cell = glm::vec<D, std::int64_t, glm::defaultp>;
    static constexpr std::uint32_t empty_key_start = 0xffffffffu;

    Cell cell_of(const Vec<D>& x) const;
    std::uint32_t key_of(const Cell& c) const;
    // Visits each candidate j != i (same key, not yet distance-checked) once.
    template <class Visit>
    void for_each_candidate(const Vec<D>& x, Visit&& visit) const;

    Real cell_size_ = 1;
    std::uint32_t table_size_ = 1;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> lookup_; // (key, particle), sorted
    std::vector<std::uint32_t> start_;                            // per key, into lookup_
};

} // namespace sph
