#include "sph/neighbours/cell_neighbourhoods.hpp"

#include "sph/headroom.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sph {

template <int D>
void CellNeighbourhoods<D>::build(std::span<const Vec<D>> fluid, std::span<const Vec<D>> walls,
                                  Real radius, const Box<D>* walls_bounds,
                                  const WallsWithin& walls_within, bool cell_runs,
                                  bool walls_inside) {
    fluid_count_ = fluid.size();
    const std::size_t fluid_count = fluid.size();
    // The walls within two cells of the fluid's box (a non-finite position
    // takes no part in the box, as in the sorted grid): every wall in the
    // 3^D cells around a fluid cell, so each cell's neighbourhood is the one
    // all walls would give, the same bits, also over MPI ranks, which see
    // the fluid's boxes of their own.
    const Box<D> fluid_box = finite_bounds(fluid);
    const Real margin = 2.001 * radius; // two cells of the grid's (radius + 2^-20)
    Box<D> near_box = fluid_box;
    for (int a = 0; a < D; ++a) {
        near_box.min[a] -= margin;
        near_box.max[a] += margin;
    }
    wall_index_.clear();
    // Through the walls' own grid when it is given: a tank's walls can
    // outnumber its fluid three to one, and reading all of them every step
    // cost 13 ns a particle-step of the 3D dam break at 97k particles.
    if (walls_within)
        walls_within(near_box, wall_index_);
    else
        for (std::size_t i = 0; i < walls.size(); ++i) {
            bool near = true;
            for (int a = 0; a < D; ++a)
                near = near && walls[i][a] >= near_box.min[a] && walls[i][a] <= near_box.max[a];
            if (near)
                wall_index_.push_back(static_cast<std::uint32_t>(i));
        }
    const std::size_t wall_count = wall_index_.size();
    resize_with_headroom(positions_, fluid_count + wall_count);
    // By every thread: copied by one, the others waited (2% of a 2D step
    // of 5,000 particles).
#pragma omp parallel
    {
#pragma omp for schedule(static) nowait
        for (std::size_t i = 0; i < fluid_count; ++i)
            positions_[i] = fluid[i];
#pragma omp for schedule(static) nowait
        for (std::size_t i = 0; i < wall_count; ++i)
            positions_[fluid_count + i] = walls[wall_index_[i]];
    }
    const auto order = !walls_bounds ? grid_.cell_order(positions_, radius)
                       : walls_inside
                           ? grid_.cell_order(positions_, radius, *walls_bounds, fluid_box)
                           : grid_.cell_order(positions_, radius, *walls_bounds);

    // Each grid cell's fluid and, for a cell with fluid, its neighbourhood.
    const std::size_t grid_cells = grid_.cell_count();
    resize_with_headroom(runs_, grid_cells);
    resize_with_headroom(run_count_, grid_cells);
    resize_with_headroom(fluid_end_, grid_cells);
    resize_with_headroom(candidates_, grid_cells);
    const auto n = static_cast<std::uint32_t>(fluid_count_);
    std::size_t most = 0;
#pragma omp parallel for schedule(static) reduction(max : most)
    for (std::size_t c = 0; c < grid_cells; ++c) {
        const std::uint32_t begin = grid_.cell_begin(c), end = grid_.cell_begin(c + 1);
        std::uint32_t k = begin;
        while (k < end && order[k] < n)
            ++k;
        fluid_end_[c] = k;
        int count = 0;
        if (k > begin && cell_runs)
            count = grid_.neighbour_runs(c, runs_[c]);
        else if (k > begin) {
            runs_[c][0] = {begin, end};
            count = 1;
        }
        run_count_[c] = static_cast<std::uint8_t>(count);
        std::uint32_t candidates = 0;
        for (int r = 0; r < count; ++r)
            candidates += runs_[c][r].end - runs_[c][r].begin;
        candidates_[c] = candidates;
        most = std::max<std::size_t>(most, candidates);
    }
    max_candidates_ = most;
    tiled_ready_ = false;
    if constexpr (D == 2)
        make_strips();
}

// By one thread: a few hundred cells for thousands of particles. The cells
// come along the Morton curve, on which a row's cells are in order of x, so
// a stable counting sort by row puts them row by row, each row in order;
// a sparse grid (rows far more than cells: a splash's stray particle) sorts
// them instead.
template <int D>
void CellNeighbourhoods<D>::make_strips() {
    by_row_.clear();
    std::uint32_t low = std::numeric_limits<std::uint32_t>::max(), high = 0;
    for (std::size_t c = 0; c < grid_.cell_count(); ++c)
        if (fluid_end_[c] > grid_.cell_begin(c)) {
            const Coordinates at = grid_.coordinates(c);
            const StripCell cell{static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(at[0]),
                                 static_cast<std::uint32_t>(at[1])};
            by_row_.push_back(cell);
            low = std::min(low, cell.y);
            high = std::max(high, cell.y);
        }
    strips_.clear();
    strip_cells_.resize(by_row_.size());
    const std::size_t rows = by_row_.empty() ? 0 : std::size_t(high - low) + 1;
    if (rows <= 4 * by_row_.size() + 64) {
        row_start_.assign(rows + 1, 0);
        for (const StripCell& cell : by_row_)
            ++row_start_[cell.y - low + 1];
        for (std::size_t r = 0; r < rows; ++r)
            row_start_[r + 1] += row_start_[r];
        for (const StripCell& cell : by_row_)
            strip_cells_[row_start_[cell.y - low]++] = cell;
    } else {
        strip_cells_ = by_row_;
        std::stable_sort(strip_cells_.begin(), strip_cells_.end(),
                         [](const StripCell& a, const StripCell& b) { return a.y < b.y; });
    }
    std::uint32_t fluid = 0;
    for (std::size_t i = 0; i < strip_cells_.size(); ++i) {
        const StripCell cell = strip_cells_[i];
        if (i == 0 || cell.y != strip_cells_[i - 1].y ||
            cell.x / strip_width != strip_cells_[i - 1].x / strip_width)
            strips_.push_back({static_cast<std::uint32_t>(i), 0, cell.y, fluid});
        strips_.back().last = static_cast<std::uint32_t>(i) + 1;
        fluid += fluid_end_[cell.cell] - grid_.cell_begin(cell.cell);
    }
    strip_fluid_ = fluid;
}

template <int D>
Real CellNeighbourhoods<D>::refresh_fluid_positions(std::span<const Vec<D>> fluid) {
    if (fluid.size() != fluid_count_)
        throw std::logic_error("CellNeighbourhoods::refresh_fluid_positions: another fluid");
    return grid_.refresh_sorted_positions(fluid, positions_);
}

template <int D>
void CellNeighbourhoods<D>::tile_cells() {
    if (tiled_ready_)
        return;
    tiled_ready_ = true;
    const std::size_t grid_cells = grid_.cell_count();
    resize_with_headroom(entry_fluid_end_, sorted_count());
#pragma omp parallel for schedule(static)
    for (std::size_t c = 0; c < grid_cells; ++c)
        std::fill(entry_fluid_end_.begin() + grid_.cell_begin(c),
                  entry_fluid_end_.begin() + grid_.cell_begin(c + 1), fluid_end_[c]);
    // The cells with fluid by their tile's colour, in Morton order within
    // each (a stable counting sort), and where each tile starts.
    auto& cells = colour_cells_;
    auto& starts = colour_tiles_;
    for (int q = 0; q < colours; ++q) {
        cells[q].clear();
        starts[q].clear();
    }
    std::array<std::uint64_t, colours> last_tile;
    last_tile.fill(~std::uint64_t{0});
    for (std::size_t c = 0; c < grid_cells; ++c) {
        if (run_count_[c] == 0)
            continue;
        int q = 0;
        const std::uint64_t tile = grid_.tile(c, q);
        if (tile != last_tile[q]) {
            starts[q].push_back(static_cast<std::uint32_t>(cells[q].size()));
            last_tile[q] = tile;
        }
        cells[q].push_back(static_cast<std::uint32_t>(c));
    }
    tiled_.clear();
    tile_start_.clear();
    for (int q = 0; q < colours; ++q) {
        colour_start_[q] = static_cast<std::uint32_t>(tile_start_.size());
        const auto base = static_cast<std::uint32_t>(tiled_.size());
        for (const std::uint32_t s : starts[q])
            tile_start_.push_back(base + s);
        tiled_.insert(tiled_.end(), cells[q].begin(), cells[q].end());
    }
    colour_start_[colours] = static_cast<std::uint32_t>(tile_start_.size());
    tile_start_.push_back(static_cast<std::uint32_t>(tiled_.size()));
}

template <int D>
typename CellNeighbourhoods<D>::Coordinates
CellNeighbourhoods<D>::tile_halo(std::size_t c, std::span<HaloCell, halo_cells> halo) const {
    Coordinates corner = grid_.coordinates(c);
    for (int a = 0; a < D; ++a)
        corner[a] = (corner[a] >> SortedGrid<D>::tile_shift << SortedGrid<D>::tile_shift) - 1;
    for (int h = 0; h < halo_cells; ++h) {
        Coordinates at;
        int rest = h;
        for (int a = 0; a < D; ++a) {
            at[a] = corner[a] + rest % halo_width;
            rest /= halo_width;
        }
        const Range r = grid_.range_at(at);
        halo[h] = {r.begin, r.end > r.begin ? entry_fluid_end_[r.begin] : r.end, r.end};
    }
    return corner;
}

template class CellNeighbourhoods<2>;
template class CellNeighbourhoods<3>;

} // namespace sph
