#pragma once
// Neighbour search on a uniform grid whose cells are ordered along a Morton
// (z-order) curve: the "z-index sort" of Ihmsen et al. 2011, "A parallel SPH
// implementation on multi-core CPUs". Cells of size h cover the particles'
// bounding box; a counting sort buckets the particles by cell (O(N), stable,
// so deterministic), and their positions are copied into that order, so a
// cell and its neighbours are contiguous runs of memory that the distance
// loop streams through. Every row lists its neighbours by ascending index, and
// the lists do not depend on the thread count.
//
// A box too large for a table indexed by Morton code (more than ~4 keys per
// particle: a splash, a stray particle) falls back to a radix sort of the
// codes and a hash table of the occupied cells; one wider than 2^21 cells
// gets coarser cells along that axis. Both stay exact, only slower.

#include "sph/neighbours/neighbour_search.hpp"
#include "sph/select_in_order.hpp"

#include <array>
#include <cstdint>
#include <vector>

namespace sph {

// The box of the finite positions (a NaN or an infinity is nobody's
// neighbour, and must not stretch a grid); min > max along every axis when
// none is finite. By all threads.
template <int D>
Box<D> finite_bounds(std::span<const Vec<D>> positions);

template <int D>
class SortedGrid final : public NeighbourSearch<D> {
  public:
    std::string_view name() const override { return "sorted_grid"; }
    void find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) override;

    // Particle indices in cell order (cells along the Morton curve, a cell's
    // particles by ascending index), as of the last find: the permutation a
    // spatial sort of the particle arrays applies. The identity after a find
    // with a radius of zero.
    const std::vector<std::uint32_t>& order() const { return order_; }
    // Sorts into cells only (no lists; the next find sorts again) and
    // returns order(): cells along the Morton curve, a cell's particles by
    // index, so it depends on the positions and the current memory order only.
    std::span<const std::uint32_t> cell_order(std::span<const Vec<D>> positions,
                                              Real radius) override;

    // cell_order with the grid laid over the box of the positions and
    // `within` together: the same grid wherever `within` bounds the
    // positions (over MPI ranks, the whole set of wall particles of which a
    // rank holds some).
    std::span<const std::uint32_t> cell_order(std::span<const Vec<D>> positions, Real radius,
                                              const Box<D>& within);
    // The same when the positions outside `within` all lie in `outside`
    // (their finite box, or larger): the grid is then laid without reading
    // the positions for their box (the walls in `within`, the fluid outside:
    // 1% of the 3D dam break's step).
    std::span<const std::uint32_t> cell_order(std::span<const Vec<D>> positions, Real radius,
                                              const Box<D>& within, const Box<D>& outside);

    // Each position's cell key (its cell's Morton code) on the grid that
    // cell_order would lay over positions whose finite bounding box is
    // [lo, hi]: cell_order sorts by these keys, stably. Over MPI ranks each
    // rank keys its own particles on the whole fluid's grid
    // (parallel/rank_partition.cpp).
    std::span<const std::uint64_t> cell_keys(std::span<const Vec<D>> positions, Real radius,
                                             const Vec<D>& lo, const Vec<D>& hi);

    // The occupied cells of the last find or cell_order, along the Morton
    // curve, for passes that work a cell at a time
    // (sph/neighbours/cell_neighbourhoods.hpp). A cell holds the particles
    // order()[cell_begin(c) .. cell_begin(c + 1)), by ascending index.
    std::size_t cell_count() const { return cell_start_.size() - 1; }
    std::uint32_t cell_begin(std::size_t c) const { return cell_start_[c]; }
    // The tile of cells that cell c is in (its coordinates over
    // 2^tile_shift, packed), and the tile's colour, 0 .. 2^D - 1 (those
    // coordinates' parities). Two tiles of one colour are at least two
    // tiles apart along some axis, so two of their cells are at least
    // 2^tile_shift + 1 >= 3 apart: their cells' 3^D neighbourhoods do not
    // overlap. A tile's cells are consecutive along the Morton curve.
    // Tiles of 4^D cells: in 3D, 1.10x on a 100k-particle dam break against
    // 2^D (too little of each tile's neighbourhood still cached) and 8^D
    // (too few tiles a colour for two threads) (docs/benchmarks.md). Fixed,
    // not sized to the scene, so that MPI ranks tile as one process does.
    static constexpr int tile_shift = 2;
    std::uint64_t tile(std::size_t c, int& colour) const;
    // A run of sorted particles: [begin, end).
    struct Range {
        std::uint32_t begin, end;
    };
    // Integer coordinates of a cell on the grid (those of occupied cell c's
    // first particle), and the particles of the cell at some coordinates:
    // empty outside the grid or where no particle is (a pass that lays out
    // a tile's neighbourhood itself, sph/single_precision/cell_passes.hpp).
    using Coordinates = std::array<std::int64_t, D>;
    Coordinates coordinates(std::size_t c) const;
    Range range_at(const Coordinates& at) const;
    // The point at grid coordinates `at` (fractions of a cell too): the
    // grid's origin plus `at` cells along each axis.
    Vec<D> grid_point(const std::array<Real, D>& at) const {
        Vec<D> x;
        for (int a = 0; a < D; ++a)
            x[a] = origin_[a] + (inverse_cell_size_[a] > 0 ? at[a] / inverse_cell_size_[a] : 0);
        return x;
    }
    // The runs of the (up to 3^D) occupied cells around cell c, c included,
    // by ascending position; returns how many.
    using NeighbourRuns = std::array<Range, D == 2 ? 9 : 27>;
    int neighbour_runs(std::size_t cell, NeighbourRuns& runs) const;
    // Copies `moved`, the first moved.size() of the positions the last
    // cell_order sorted (`sorted`, indexed as then), into the sorted arrays
    // without sorting again: the cells stay those of `sorted`, which a
    // caller keeps exact by a skin (sph/neighbours/cell_neighbourhoods.hpp).
    // Returns the largest squared distance from a position in `sorted` to
    // its moved one (infinite for one not finite). By all threads.
    Real refresh_sorted_positions(std::span<const Vec<D>> moved, std::span<const Vec<D>> sorted);
    // The positions in cell order, one array per axis. sorted_tail more
    // entries follow each in memory, readable (their values mean nothing):
    // a loop may copy whole vectors past a run's end.
    static constexpr std::size_t sorted_tail = 16;
    std::span<const Real> sorted_positions(int axis) const {
        return {sorted_x_[axis].data(), order_.size()};
    }

    // Whether the last find hashed the occupied cells (a sparse or huge box)
    // instead of indexing a table by Morton code.
    bool hashed_cells() const { return hashed_; }

    // Wall-clock seconds of the last find: sorting into cells, then listing.
    struct Timings {
        double build_seconds = 0;
        double query_seconds = 0;
    };
    const Timings& last_timings() const { return timings_; }

  private:
    using Coord = std::array<std::uint32_t, D>;
    // Per-thread buffers, kept between calls.
    struct Scratch {
        std::vector<std::uint64_t> keyed;    // (index << 32 | sorted position) per candidate
        std::vector<std::uint64_t> merged;   // keyed's runs, merged (sort_by_index)
        std::vector<std::uint32_t> run_ends; // where keyed's ascending runs end
        std::array<std::vector<Real>, D> x;  // the candidates of one cell, gathered
        std::vector<std::uint32_t> index;    // their indices in the caller's order
        std::vector<Real> distance2;
        std::vector<std::uint32_t> rows; // this thread's neighbour rows, any order
    };

    void sort_into_cells(std::span<const Vec<D>> positions, Real radius);
    // The cells over the box [lo, hi] (lo > hi along an axis: no finite
    // position); returns the Morton key's bits.
    int set_up_grid(Vec<D> lo, Vec<D> hi, Real radius);
    void set_up_morton(const std::array<std::uint32_t, D>& bits);
    // These three run for every particle each step: inline, for a call to
    // cell_of returned its coordinates through memory and stalled on them
    // (the keys took 10 ns a particle-step of the 3D dam break).
    Coord cell_of(const Vec<D>& x) const {
        Coord c;
        for (int a = 0; a < D; ++a) {
            const Real u = (x[a] - origin_[a]) * inverse_cell_size_[a];
            const Real top = Real(cell_count_[a] - 1);
            // A NaN or infinity lands in a border cell; it is nobody's neighbour.
            c[a] = u > 0 ? static_cast<std::uint32_t>(u < top ? u : top) : 0;
        }
        return c;
    }
    std::uint64_t morton(const Coord& c) const {
        std::uint64_t code = 0;
        for (int a = 0; a < D; ++a)
            code |= spread(a, c[a]);
        return code;
    }
    std::uint64_t spread(int axis, std::uint32_t c) const {
        const auto& s = spread_[axis];
        return s[0][c & 0xff] | s[1][c >> 8 & 0xff] | s[2][c >> 16 & 0xff];
    }
    void counting_sort(std::size_t key_count);
    void split_codes(std::size_t key_count, std::size_t threads);
    void radix_sort(int key_bits);
    void hash_cells();
    Range cell_range(std::uint64_t key) const;
    // Gathers into s the candidates of the particles of one cell, ordered by
    // index; returns how many.
    std::size_t gather_candidates(std::size_t cell, Real r2, Scratch& s) const;
    // Sorts s.keyed[0, count) by merging its ascending runs.
    static void sort_by_index(std::size_t count, Scratch& s);
    void list_neighbours(Real radius, NeighbourList& out);
    // Sets the identity order when `positions` are the last cell_order's
    // sorted (sorted_for_order_); whether it did.
    bool sorted_in_place(std::span<const Vec<D>> positions, Real radius);

    // A box the grid covers besides the positions (cell_order's `within`).
    const Box<D>* within_ = nullptr;
    // Whether the last call was a cell_order over the positions' own box
    // at sorted_radius_: if the next find's positions are those positions
    // permuted by order() (a spatial sort of the particle arrays, as the
    // run loop does between the two), its grid is this one with the
    // identity order, and find sorts nothing (sorted_grid.cpp).
    bool sorted_for_order_ = false;
    Real sorted_radius_ = 0;
    // The box of the positions outside within_ (cell_order's `outside`).
    const Box<D>* outside_ = nullptr;
    // The grid of the last call.
    Vec<D> origin_{0};
    Vec<D> inverse_cell_size_{1};
    Coord cell_count_{};
    std::array<std::uint32_t, D> bits_{};
    // Morton code of a coordinate, one byte at a time: spread_[axis][byte][value].
    std::array<std::array<std::array<std::uint64_t, 256>, 3>, D> spread_{};
    bool morton_ready_ = false;
    bool hashed_ = false;

    std::vector<std::uint64_t> keys_;        // Morton code per particle, caller's order
    std::vector<std::uint64_t> sorted_keys_; // in cell order
    std::vector<std::uint64_t> key_buffer_;  // radix sort
    std::vector<std::uint32_t> order_;
    std::vector<std::uint32_t> order_buffer_;   // radix sort
    std::array<std::vector<Real>, D> sorted_x_; // positions in cell order, one array per axis
    std::vector<std::uint32_t> key_start_;      // table: first sorted particle per key, + end
    // counting_sort: the particles and occupied cells in each thread's codes.
    struct RangeTotal {
        std::uint32_t particles = 0, cells = 0;
    };
    std::vector<RangeTotal> range_totals_;
    std::vector<std::uint64_t> range_cuts_, code_sample_; // split_codes
    SelectInOrder starts_;                  // the hashed cells' starts (sort_into_cells)
    std::vector<std::uint32_t> cell_start_; // occupied cells: first sorted particle, + end
    std::vector<std::uint64_t> hash_keys_;  // open addressing, empty = ~0
    std::vector<std::uint32_t> hash_cells_; // cell number per slot
    int hash_shift_ = 64;

    std::vector<Scratch> scratch_;
    std::vector<std::uint32_t> row_offset_; // per particle, into its thread's rows
    std::vector<std::uint16_t> row_thread_;
    Timings timings_;
};

} // namespace sph
