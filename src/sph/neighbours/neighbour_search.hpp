#pragma once
// The interface every neighbour search implements, and the factory that picks
// one by the name used in scenes (`solver.neighbour_search`).

#include "sph/neighbours/neighbour_list.hpp"
#include "sph/vec.hpp"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

template <int D>
class NeighbourSearch {
  public:
    virtual ~NeighbourSearch() = default;
    virtual std::string_view name() const = 0;
    // Lists, for every particle, the other particles closer than `radius`
    // (strictly). Reuses the memory of `out` and of the search between calls.
    virtual void find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) = 0;
    // The particle indices in the order of cells of size `radius` at these
    // positions (the permutation a spatial sort of the particle arrays
    // applies), valid until the next call; empty when the search keeps no
    // cells in an order worth sorting by. Lists nothing.
    virtual std::span<const std::uint32_t> cell_order(std::span<const Vec<D>> /*positions*/,
                                                      Real /*radius*/) {
        return {};
    }
    // Only the rows of particles [begin, end) are wanted by the next finds
    // (over MPI ranks, a rank's own particles: its halo's rows are never
    // read); a search may leave the others empty. All by default.
    void want_rows(std::size_t begin, std::size_t end) {
        rows_begin_ = begin;
        rows_end_ = end;
    }

  protected:
    std::size_t rows_begin_ = 0, rows_end_ = ~std::size_t(0);
};

// The neighbour searches (solver.neighbour_search), in the order of
// neighbour_search_names().
enum class NeighbourSearchKind { hash, sorted_grid, all_pairs };

// Names accepted by make_neighbour_search, in the order docs/scene-keys.md lists them.
std::vector<std::string> neighbour_search_names();

template <int D>
std::unique_ptr<NeighbourSearch<D>> make_neighbour_search(NeighbourSearchKind kind);
// By name, one of neighbour_search_names(); throws std::invalid_argument for another.
template <int D>
std::unique_ptr<NeighbourSearch<D>> make_neighbour_search(std::string_view name);

} // namespace sph
