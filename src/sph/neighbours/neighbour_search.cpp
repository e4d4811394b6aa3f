#include "sph/neighbours/neighbour_search.hpp"

#include "sph/neighbours/all_pairs.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <stdexcept>

namespace sph {

std::vector<std::string> neighbour_search_names() {
    return {"hash", "sorted_grid", "all_pairs"};
}

template <int D>
std::unique_ptr<NeighbourSearch<D>> make_neighbour_search(NeighbourSearchKind kind) {
    switch (kind) {
    case NeighbourSearchKind::hash:
        return std::make_unique<SpatialHash<D>>();
    case NeighbourSearchKind::sorted_grid:
        return std::make_unique<SortedGrid<D>>();
    case NeighbourSearchKind::all_pairs:
        return std::make_unique<AllPairs<D>>();
    }
    throw std::invalid_argument("unknown neighbour search");
}

template <int D>
std::unique_ptr<NeighbourSearch<D>> make_neighbour_search(std::string_view name) {
    const auto names = neighbour_search_names();
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end())
        throw std::invalid_argument("unknown neighbour search: " + std::string(name));
    return make_neighbour_search<D>(static_cast<NeighbourSearchKind>(at - names.begin()));
}

template std::unique_ptr<NeighbourSearch<2>> make_neighbour_search<2>(NeighbourSearchKind);
template std::unique_ptr<NeighbourSearch<3>> make_neighbour_search<3>(NeighbourSearchKind);
template std::unique_ptr<NeighbourSearch<2>> make_neighbour_search<2>(std::string_view);
template std::unique_ptr<NeighbourSearch<3>> make_neighbour_search<3>(std::string_view);

} // namespace sph
