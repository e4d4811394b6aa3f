#pragma once
// The fluid's grid cells and, for each, the runs of particles in the 3^D
// cells around it: what a pass that works a cell at a time reads instead of
// neighbour lists (the single-precision passes, sph/single_precision/).
//
// Fluid and wall particles are sorted together into one sorted grid
// (sph/neighbours/sorted_grid.hpp), so a cell's neighbourhood holds both:
// sorted entry k is fluid particle order()[k] when that is below
// fluid_count(), else wall particle wall(order()[k] - fluid_count()). A cell
// lists its particles by ascending index, so its fluid ones come first.
// Only the walls within two cells of the fluid's box are sorted: the others
// are in no fluid cell's neighbourhood, and in 3D a tank's walls can
// outnumber its fluid (sorting them all every step was most of a small 3D
// scene's neighbour cells).
//
// No distance is tested here and nothing is listed per particle: the pass
// gathers a cell's neighbourhood into contiguous buffers once and runs every
// particle of the cell over all of it, a lane per candidate, the candidates
// farther than the radius adding 0. That trades about three times more
// pair evaluations for loops without gathers and no lists to write.

#include "sph/neighbours/sorted_grid.hpp"

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace sph {

template <int D>
class CellNeighbourhoods {
  public:
    using Range = typename SortedGrid<D>::Range;

    // Appends to its vector, in increasing order, the walls inside a box
    // (faces included), as BoundaryParticles::within does.
    using WallsWithin = std::function<void(const Box<D>&, std::vector<std::uint32_t>&)>;

    // Sorts the fluid and wall particles into cells of size `radius` (> 0),
    // on a grid that covers `walls_bounds` too when given (the whole set's
    // box when `walls` are some of it: BoundaryParticles::static_bounds).
    // `walls_within`, when given, lists the walls near the fluid without
    // reading them all. Without `cell_runs` a cell's runs are its own
    // particles only: for a pass that reads tile_halo instead (3D, each
    // pair once), to which the 27 lookups a cell cost 3% of the step, or
    // strips() (2D).
    // `walls_inside`: every wall lies in `walls_bounds` (none moves), so the
    // grid's box is the fluid's and that one, found without reading the walls.
    void build(std::span<const Vec<D>> fluid, std::span<const Vec<D>> walls, Real radius,
               const Box<D>* walls_bounds = nullptr, const WallsWithin& walls_within = {},
               bool cell_runs = true, bool walls_inside = false);

    // The fluid's sorted positions set to these (the same particles as the
    // last build's, indexed as then), the cells and their runs kept: for
    // cells made at earlier positions and wide enough to still hold every
    // pair within reach (a skin: sph/single_precision/single_passes.hpp).
    // The walls' stay: they must not have moved. Returns the largest squared
    // distance of a fluid particle from where the build had it (infinite
    // for one not finite).
    Real refresh_fluid_positions(std::span<const Vec<D>> fluid);

    std::size_t fluid_count() const { return fluid_count_; }
    // The wall particle (an index into build's `walls`) that sorted wall
    // entry w = order()[k] - fluid_count() is.
    std::uint32_t wall(std::size_t w) const { return wall_index_[w]; }
    // The particle (fluid, then wall) at each sorted position.
    std::span<const std::uint32_t> order() const { return grid_.order(); }
    // Positions in sorted order, one array per axis.
    std::span<const Real> sorted_positions(int axis) const { return grid_.sorted_positions(axis); }

    // The grid's cells along the Morton curve (those without fluid
    // included: a pass skips them), each with its fluid particles and the
    // runs of the cells around it.
    struct Cell {
        std::uint32_t begin, fluid_end; // its fluid particles, sorted positions
        std::span<const Range> runs;    // the 3^D cells around it, itself included
        std::uint32_t candidates;       // particles in its runs
        bool has_fluid() const { return fluid_end > begin; }
    };
    std::size_t cell_count() const { return grid_.cell_count(); }
    Cell cell(std::size_t c) const {
        return {
            grid_.cell_begin(c), fluid_end_[c], {runs_[c].data(), run_count_[c]}, candidates_[c]};
    }
    // For a pass that takes each fluid pair once (solver.pair_terms), after
    // tile_cells (by one thread, once after each build; the rest of this
    // block is valid after it):
    void tile_cells();
    // Where the fluid of the cell that `run` (one of a Cell's runs) is ends:
    // its wall particles are [fluid_end(run), run.end).
    std::uint32_t fluid_end(const Range& run) const { return entry_fluid_end_[run.begin]; }
    // The tiles of cells of colour q (SortedGrid::tile): no two share a
    // particle of their cells' neighbourhoods, so a pass may write into
    // its neighbours' sums for all of them at once, a tile a thread. Tile t
    // of colour q holds the cells with fluid tiled_cells()[tile_start(q, t)
    // .. tile_start(q, t + 1)), along the Morton curve.
    static constexpr int colours = 1 << D;
    std::size_t tile_count(int q) const { return colour_start_[q + 1] - colour_start_[q]; }
    std::uint32_t tile_start(int q, std::size_t t) const {
        return tile_start_[colour_start_[q] + t];
    }
    std::span<const std::uint32_t> tiled_cells() const { return tiled_; }
    // Tile t of colour q among all the tiles, 0 .. tiles() - 1.
    std::size_t tile_index(int q, std::size_t t) const { return colour_start_[q] + t; }
    std::size_t tiles() const { return colour_start_[colours]; }

    // For a pass that copies each tile's neighbourhood once (3D, after
    // tile_cells): a tile's cells and the cells around it, halo_width^D of
    // them, x fastest, each with its fluid [begin, fluid_end) and walls
    // [fluid_end, end) in sorted order. tile_halo fills them for the tile
    // of cell c and returns the grid coordinates of the first.
    using Coordinates = typename SortedGrid<D>::Coordinates;
    static constexpr int halo_width = (1 << SortedGrid<D>::tile_shift) + 2;
    static constexpr int halo_cells =
        D == 2 ? halo_width * halo_width : halo_width * halo_width * halo_width;
    struct HaloCell {
        std::uint32_t begin, fluid_end, end;
    };
    Coordinates tile_halo(std::size_t c, std::span<HaloCell, halo_cells> halo) const;
    Coordinates coordinates(std::size_t c) const { return grid_.coordinates(c); }

    // 2D, after each build: the cells with fluid row by row (y, then x), in
    // strips of at most strip_width cells of one row that share x /
    // strip_width. A pass copies the three rows around a strip once, a
    // column of three cells after another, so that each cell's 3 x 3
    // neighbourhood is one run of the copy (sph/single_precision/
    // cell_passes.hpp); a strip's columns fixed on the grid, not by where a
    // thread starts, keep the copies' offsets and the sums' order the same
    // with any thread count. fluid_before: the fluid particles of the strips
    // before, for splitting them among threads.
    static constexpr int strip_width = 8;
    struct StripCell {
        std::uint32_t cell, x, y; // the cell, its column and row
    };
    struct Strip {
        std::uint32_t first, last; // its cells: strip_cells()[first .. last)
        std::uint32_t y;           // its row
        std::uint32_t fluid_before;
    };
    std::span<const Strip> strips() const { return strips_; }
    std::span<const StripCell> strip_cells() const { return strip_cells_; }
    std::size_t strip_fluid() const { return strip_fluid_; } // all the strips' fluid
    Range range_at(const Coordinates& at) const { return grid_.range_at(at); }
    Vec<D> grid_point(const std::array<Real, D>& at) const { return grid_.grid_point(at); }

    // The most candidates of any cell with fluid (its runs'): the size of a
    // pass's buffers, which a 2D pass grows to a strip's copy.
    std::size_t max_candidates() const { return max_candidates_; }
    // Sorted entries (fluid and walls).
    std::size_t sorted_count() const { return grid_.order().size(); }

  private:
    SortedGrid<D> grid_;
    std::vector<Vec<D>> positions_;         // fluid then walls, as built
    std::vector<std::uint32_t> wall_index_; // the walls sorted, by index
    std::size_t fluid_count_ = 0;
    // Per grid cell.
    std::vector<typename SortedGrid<D>::NeighbourRuns> runs_;
    std::vector<std::uint8_t> run_count_;
    std::vector<std::uint32_t> fluid_end_, candidates_;
    std::vector<std::uint32_t> entry_fluid_end_; // per sorted entry: its cell's fluid_end_
    bool tiled_ready_ = false;
    std::vector<std::uint32_t> tiled_;      // cells with fluid, by tile's colour, then tile
    std::vector<std::uint32_t> tile_start_; // into tiled_, by colour then tile, + end
    std::array<std::uint32_t, colours + 1> colour_start_{}; // into tile_start_
    // tile_cells' scratch, kept between steps: by colour, the cells and
    // where each tile starts among them.
    std::array<std::vector<std::uint32_t>, colours> colour_cells_, colour_tiles_;
    std::size_t max_candidates_ = 0;
    // 2D: strips() and their scratch.
    void make_strips();
    std::vector<Strip> strips_;
    std::vector<StripCell> strip_cells_, by_row_;
    std::vector<std::uint32_t> row_start_;
    std::size_t strip_fluid_ = 0;
};

} // namespace sph
