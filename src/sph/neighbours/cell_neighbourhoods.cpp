#include "sph/neighbours/cell_neighbourhoods.hpp"

#include "sph/headroom.hpp"

#include <algorithm>

namespace sph {

template <int D>
void CellNeighbourhoods<D>::build(std::span<const Vec<D>> fluid, std::span<const Vec<D>> walls,
                                  Real radius) {
    fluid_count_ = fluid.size();
    resize_with_headroom(positions_, fluid.size() + walls.size());
    std::copy(fluid.begin(), fluid.end(), positions_.begin());
    std::copy(walls.begin(), walls.end(), positions_.begin() + std::ptrdiff_t(fluid.size()));
    const auto order = grid_.cell_order(positions_, radius);

    // Each grid cell's fluid and its neighbourhood, in parallel; then the
    // cells with fluid, in Morton order.
    const std::size_t grid_cells = grid_.cell_count();
    resize_with_headroom(grid_runs_, grid_cells);
    resize_with_headroom(run_count_, grid_cells);
    resize_with_headroom(fluid_end_, grid_cells);
    const auto n = static_cast<std::uint32_t>(fluid_count_);
#pragma omp parallel for schedule(static)
    for (std::size_t c = 0; c < grid_cells; ++c) {
        const std::uint32_t begin = grid_.cell_begin(c), end = grid_.cell_begin(c + 1);
        std::uint32_t k = begin;
        while (k < end && order[k] < n)
            ++k;
        fluid_end_[c] = k;
        run_count_[c] = k > begin ? static_cast<std::uint8_t>(grid_.neighbour_runs(c, grid_runs_[c]))
                                  : 0;
    }
    // Reserved with headroom, so that pushing allocates nothing in a step.
    constexpr std::size_t most_runs = D == 2 ? 9 : 27;
    if (cells_.capacity() < grid_cells)
        cells_.reserve(grid_cells + grid_cells / 4);
    if (runs_.capacity() < most_runs * grid_cells)
        runs_.reserve(most_runs * (grid_cells + grid_cells / 4));
    cells_.clear();
    runs_.clear();
    max_candidates_ = candidate_count_ = 0;
    for (std::size_t c = 0; c < grid_cells; ++c) {
        const std::uint32_t begin = grid_.cell_begin(c);
        if (fluid_end_[c] == begin)
            continue;
        Cell cell{begin, fluid_end_[c], static_cast<std::uint32_t>(runs_.size()), 0, 0};
        for (int r = 0; r < run_count_[c]; ++r) {
            runs_.push_back(grid_runs_[c][r]);
            cell.candidates += grid_runs_[c][r].end - grid_runs_[c][r].begin;
        }
        cell.runs_end = static_cast<std::uint32_t>(runs_.size());
        max_candidates_ = std::max<std::size_t>(max_candidates_, cell.candidates);
        candidate_count_ += std::size_t(cell.candidates) * (cell.fluid_end - cell.begin);
        cells_.push_back(cell);
    }
}

template class CellNeighbourhoods<2>;
template class CellNeighbourhoods<3>;

} // namespace sph
