#include "sph/neighbours/sorted_grid.hpp"

#include "sph/headroom.hpp"
#include "sph/neighbours/distance_filter.hpp"
#include "sph/vector_clones.hpp"
#include "sph/wall_clock.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <omp.h>
#include <stdexcept>

namespace sph {

namespace {

// Cells per axis at most: 21 bits an axis keep a 3D Morton code in 63 bits.
constexpr std::uint32_t max_axis_cells = 1u << 21;
// Cells a hair wider than the radius, so that rounding in (x - origin) / size
// can never put two particles closer than the radius two cells apart.
constexpr Real cell_widening = 1 + 0x1p-20;
// A table indexed by Morton code while it needs at most this many entries per
// particle (or min_table_keys); a sparser box hashes its occupied cells.
constexpr std::size_t table_keys_per_particle = 8;
constexpr std::size_t min_table_keys = 1 << 16;
constexpr int radix_bits = 11;
constexpr std::uint64_t empty_slot = ~std::uint64_t(0);

inline Real positive_part(Real v) {
    return v > 0 ? v : 0;
}

// Squared distances from the candidates to a box [lo, hi], likewise (at most
// one of the two parts of a gap is non-zero).
void squared_gaps(std::size_t count, const Real* __restrict x, const Real* __restrict y, Real x_lo,
                  Real x_hi, Real y_lo, Real y_hi, Real* __restrict out) {
    for (std::size_t m = 0; m < count; ++m) {
        const Real dx = positive_part(x_lo - x[m]) + positive_part(x[m] - x_hi);
        const Real dy = positive_part(y_lo - y[m]) + positive_part(y[m] - y_hi);
        out[m] = dx * dx + dy * dy;
    }
}

void squared_gaps(std::size_t count, const Real* __restrict x, const Real* __restrict y,
                  const Real* __restrict z, Real x_lo, Real x_hi, Real y_lo, Real y_hi, Real z_lo,
                  Real z_hi, Real* __restrict out) {
    for (std::size_t m = 0; m < count; ++m) {
        const Real dx = positive_part(x_lo - x[m]) + positive_part(x[m] - x_hi);
        const Real dy = positive_part(y_lo - y[m]) + positive_part(y[m] - y_hi);
        const Real dz = positive_part(z_lo - z[m]) + positive_part(z[m] - z_hi);
        out[m] = dx * dx + dy * dy + dz * dz;
    }
}

} // namespace

template <int D>
void SortedGrid<D>::set_up_morton(const std::array<std::uint32_t, D>& bits) {
    if (morton_ready_ && bits == bits_)
        return;
    bits_ = bits;
    morton_ready_ = true;
    // Bit positions of each axis in the code, interleaved x y z x y z ...; an
    // axis that needs fewer bits drops out, so a long thin box keeps short codes.
    std::array<std::array<int, 21>, D> position{};
    int next = 0;
    for (std::uint32_t level = 0; level < 21; ++level) {
        bool any = false;
        for (int a = 0; a < D; ++a)
            if (level < bits[a]) {
                position[a][level] = next++;
                any = true;
            }
        if (!any)
            break;
    }
    for (int a = 0; a < D; ++a)
        for (int byte = 0; byte < 3; ++byte)
            for (std::uint32_t v = 0; v < 256; ++v) {
                std::uint64_t code = 0;
                for (std::uint32_t bit = 0; bit < 8; ++bit) {
                    const std::uint32_t level = 8 * byte + bit;
                    if ((v >> bit & 1) && level < bits[a])
                        code |= std::uint64_t(1) << position[a][level];
                }
                spread_[a][byte][v] = code;
            }
}

// Counting sort by Morton code (stable: a cell's particles by index), leaving
// key_start_[k] = first sorted particle of code k for k in [0, key_count],
// and the occupied cells' starts in cell_start_.
// Each thread takes a range of codes: it clears, counts, sums and scatters
// its own part of the table, reading all the codes (serial, this was 3.6%
// of the 3D dam break's step at 97k particles, while the other thread
// waited). The ranges are cut where a sample of the codes says the work is
// even (split_codes). The result is the same with any thread count.
template <int D>
void SortedGrid<D>::counting_sort(std::size_t key_count) {
    const std::size_t n = keys_.size();
    // The fluid's box grows a little at a time (sph/headroom.hpp).
    resize_with_headroom(key_start_, key_count + 1);
    const int threads = omp_get_max_threads();
    range_totals_.resize(std::size_t(threads));
    split_codes(key_count, std::size_t(threads));
    key_start_[0] = 0;
#pragma omp parallel num_threads(threads)
    {
        // Code k counts in key_start_[k + 1]; that entry then becomes the
        // next free place for code k, and at the end k's end, k + 1's start.
        const auto t = std::size_t(omp_get_thread_num());
        const auto count = std::size_t(omp_get_num_threads());
        // Fewer threads than asked for: each takes its share of the cuts.
        const std::uint64_t lo = range_cuts_[t * threads / count],
                            hi = range_cuts_[(t + 1) * threads / count];
        std::uint32_t* const table = key_start_.data() + 1;
        std::fill(table + lo, table + hi, 0u);
        const auto ours = [&](std::uint64_t key) {
            return key - lo < hi - lo;
        };
        for (std::size_t i = 0; i < n; ++i)
            if (ours(keys_[i]))
                ++table[keys_[i]];
        RangeTotal total{};
        for (std::uint64_t k = lo; k < hi; ++k) {
            const std::uint32_t c = table[k];
            table[k] = total.particles;
            total.particles += c;
            total.cells += c != 0 ? 1 : 0;
        }
        range_totals_[t] = total;
#pragma omp barrier
#pragma omp single
        {
            std::uint32_t cells = 0;
            for (std::size_t u = 0; u < count; ++u)
                cells += range_totals_[u].cells;
            resize_with_headroom(cell_start_, cells + 1);
            cell_start_[cells] = static_cast<std::uint32_t>(n);
        }
        RangeTotal offset{};
        for (std::size_t u = 0; u < t; ++u) {
            offset.particles += range_totals_[u].particles;
            offset.cells += range_totals_[u].cells;
        }
        for (std::size_t i = 0; i < n; ++i)
            if (ours(keys_[i])) {
                const std::uint32_t to = offset.particles + table[keys_[i]]++;
                order_[to] = static_cast<std::uint32_t>(i);
                sorted_keys_[to] = keys_[i];
            }
        std::uint32_t start = offset.particles, cell = offset.cells;
        for (std::uint64_t k = lo; k < hi; ++k) {
            const std::uint32_t end = offset.particles + table[k];
            if (end != start)
                cell_start_[cell++] = start;
            table[k] = end;
            start = end;
        }
    }
}

// range_cuts_[t] .. range_cuts_[t + 1]: the codes thread t of `threads`
// sorts, cut so that each range costs about the same: a code's entry of the
// table about one unit (cleared, summed, offset), a particle about three
// (counted and scattered, at random), estimated from a sample of the codes.
// A dam break's fluid fills the low codes first (Morton order from the
// box's corner): cut evenly by code, one thread had most of the particles.
template <int D>
void SortedGrid<D>::split_codes(std::size_t key_count, std::size_t threads) {
    constexpr std::size_t samples_per_thread = 64;
    constexpr double particle_cost = 3;
    const std::size_t n = keys_.size();
    const std::size_t samples = std::min(n, samples_per_thread * threads);
    code_sample_.resize(samples);
    for (std::size_t j = 0; j < samples; ++j)
        code_sample_[j] = keys_[j * n / samples];
    std::sort(code_sample_.begin(), code_sample_.end());
    range_cuts_.resize(threads + 1);
    range_cuts_[0] = 0;
    range_cuts_[threads] = key_count;
    const double total = double(key_count) + particle_cost * double(n);
    std::size_t j = 0;
    for (std::size_t t = 1; t < threads; ++t) {
        // The first sampled code with this share of the work below it.
        const double share = total * double(t) / double(threads);
        while (j < samples &&
               double(code_sample_[j]) + particle_cost * double(n) * double(j) / double(samples) <
                   share)
            ++j;
        range_cuts_[t] = j < samples ? code_sample_[j] : key_count;
    }
}

// LSD radix sort of the codes, a counting sort per 11-bit digit (stable).
template <int D>
void SortedGrid<D>::radix_sort(int key_bits) {
    const std::size_t n = keys_.size();
    std::copy(keys_.begin(), keys_.end(), sorted_keys_.begin());
    std::iota(order_.begin(), order_.end(), 0u);
    key_buffer_.resize(n);
    order_buffer_.resize(n);
    std::array<std::uint32_t, (1u << radix_bits) + 1> start;
    for (int shift = 0; shift < key_bits; shift += radix_bits) {
        start.fill(0);
        for (std::size_t i = 0; i < n; ++i)
            ++start[(sorted_keys_[i] >> shift & ((1u << radix_bits) - 1)) + 1];
        std::partial_sum(start.begin(), start.end(), start.begin());
        for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t to = start[sorted_keys_[i] >> shift & ((1u << radix_bits) - 1)]++;
            key_buffer_[to] = sorted_keys_[i];
            order_buffer_[to] = order_[i];
        }
        sorted_keys_.swap(key_buffer_);
        order_.swap(order_buffer_);
    }
}

// Open addressing with linear probing, Fibonacci hashing of the code.
template <int D>
void SortedGrid<D>::hash_cells() {
    const std::size_t cells = cell_start_.size() - 1;
    const std::size_t slots = std::bit_ceil(std::max<std::size_t>(2 * cells, 2));
    hash_shift_ = 64 - std::countr_zero(slots);
    hash_keys_.assign(slots, empty_slot);
    hash_cells_.resize(slots);
    for (std::size_t c = 0; c < cells; ++c) {
        const std::uint64_t key = sorted_keys_[cell_start_[c]];
        std::size_t slot = (key * 0x9e3779b97f4a7c15u) >> hash_shift_;
        while (hash_keys_[slot] != empty_slot)
            slot = (slot + 1) & (slots - 1);
        hash_keys_[slot] = key;
        hash_cells_[slot] = static_cast<std::uint32_t>(c);
    }
}

template <int D>
typename SortedGrid<D>::Range SortedGrid<D>::cell_range(std::uint64_t key) const {
    if (!hashed_)
        return {key_start_[key], key_start_[key + 1]};
    const std::size_t mask = hash_keys_.size() - 1;
    for (std::size_t slot = (key * 0x9e3779b97f4a7c15u) >> hash_shift_;; slot = (slot + 1) & mask) {
        if (hash_keys_[slot] == key) {
            const std::uint32_t c = hash_cells_[slot];
            return {cell_start_[c], cell_start_[c + 1]};
        }
        if (hash_keys_[slot] == empty_slot)
            return {0, 0};
    }
}

template <int D>
int SortedGrid<D>::set_up_grid(Vec<D> lo, Vec<D> hi, Real radius) {
    std::array<std::uint32_t, D> bits;
    int key_bits = 0;
    for (int a = 0; a < D; ++a) {
        if (lo[a] > hi[a])
            lo[a] = hi[a] = 0; // no finite position
        const Real extent = hi[a] - lo[a];
        Real size = radius * cell_widening;
        // Coarser cells along an axis wider than max_axis_cells: still exact
        // (a pair is at most one cell apart), only more candidates.
        if (!(extent / size < Real(max_axis_cells - 1)))
            size = extent / Real(max_axis_cells - 1);
        inverse_cell_size_[a] =
            size > 0 && size < std::numeric_limits<Real>::infinity() ? 1 / size : 0;
        const Real last = std::floor(extent * inverse_cell_size_[a]);
        cell_count_[a] =
            last < Real(max_axis_cells - 1) ? static_cast<std::uint32_t>(last) + 1 : max_axis_cells;
        bits[a] = static_cast<std::uint32_t>(std::bit_width(cell_count_[a] - 1));
        key_bits += static_cast<int>(bits[a]);
    }
    origin_ = lo;
    set_up_morton(bits);
    return key_bits;
}

template <int D>
std::span<const std::uint64_t> SortedGrid<D>::cell_keys(std::span<const Vec<D>> positions,
                                                        Real radius, const Vec<D>& lo,
                                                        const Vec<D>& hi) {
    sorted_for_order_ = false; // another grid
    set_up_grid(lo, hi, radius);
    const std::size_t n = positions.size();
    keys_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        keys_[i] = morton(cell_of(positions[i]));
    // The next find or cell_order sets the grid up again from its positions.
    return keys_;
}

template <int D>
Box<D> finite_bounds(std::span<const Vec<D>> positions) {
    Real lo[D], hi[D];
    for (int a = 0; a < D; ++a) {
        lo[a] = std::numeric_limits<Real>::max();
        hi[a] = std::numeric_limits<Real>::lowest();
    }
    const std::size_t n = positions.size();
#pragma omp parallel for schedule(static) reduction(min : lo[:D]) reduction(max : hi[:D])
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) {
            const Real x = positions[i][a];
            if (std::abs(x) <= std::numeric_limits<Real>::max()) {
                lo[a] = std::min(lo[a], x);
                hi[a] = std::max(hi[a], x);
            }
        }
    Box<D> box;
    for (int a = 0; a < D; ++a) {
        box.min[a] = lo[a];
        box.max[a] = hi[a];
    }
    return box;
}

template <int D>
void SortedGrid<D>::sort_into_cells(std::span<const Vec<D>> positions, Real radius) {
    const std::size_t n = positions.size();
    sorted_for_order_ = false; // cell_order sets it again

    auto [lo, hi] = outside_ ? *outside_ : finite_bounds(positions);
    if (within_)
        for (int a = 0; a < D; ++a)
            if (within_->min[a] <= within_->max[a]) {
                lo[a] = std::min(lo[a], within_->min[a]);
                hi[a] = std::max(hi[a], within_->max[a]);
            }
    const int key_bits = set_up_grid(lo, hi, radius);

    keys_.resize(n);
    sorted_keys_.resize(n);
    order_.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        keys_[i] = morton(cell_of(positions[i]));

    const std::size_t table_keys = std::max(table_keys_per_particle * n, min_table_keys);
    hashed_ = key_bits > 40 || (std::size_t(1) << key_bits) > table_keys;
    // The occupied cells in Morton order: where each code's run starts.
    if (!hashed_)
        counting_sort(std::size_t(1) << key_bits);
    else {
        radix_sort(key_bits);
        cell_start_.clear();
        starts_.clear();
        starts_.add(0, static_cast<std::uint32_t>(n));
        starts_.append_to(cell_start_, [&](std::uint32_t k) {
            return k == 0 || sorted_keys_[k] != sorted_keys_[k - 1];
        });
        cell_start_.push_back(static_cast<std::uint32_t>(n));
        hash_cells();
    }

    // Positions in cell order, an array per axis: neighbouring cells are then
    // contiguous runs that the distance loop streams through.
    for (int a = 0; a < D; ++a)
        resize_with_headroom(sorted_x_[a], n + sorted_tail);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < n; ++k)
        for (int a = 0; a < D; ++a)
            sorted_x_[a][k] = positions[order_[k]][a];
}

template <int D>
Real SortedGrid<D>::refresh_sorted_positions(std::span<const Vec<D>> moved,
                                             std::span<const Vec<D>> sorted) {
    sorted_for_order_ = false;
    const std::size_t n = order_.size(), count = moved.size();
    Real most = 0;
#pragma omp parallel for schedule(static) reduction(max : most)
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t i = order_[k];
        if (i >= count)
            continue;
        const Vec<D> x = moved[i], d = x - sorted[i];
        const Real d2 = glm::dot(d, d);
        most = std::max(most, d2 == d2 ? d2 : std::numeric_limits<Real>::infinity());
        for (int a = 0; a < D; ++a)
            sorted_x_[a][k] = x[a];
    }
    return most;
}

template <int D>
std::uint64_t SortedGrid<D>::tile(std::size_t cell, int& colour) const {
    const Coordinates at = coordinates(cell);
    std::uint64_t key = 0;
    colour = 0;
    for (int a = D - 1; a >= 0; --a) {
        key = key << 21 | std::uint64_t(at[a] >> tile_shift);
        colour = 2 * colour + int(at[a] >> tile_shift & 1);
    }
    return key;
}

template <int D>
typename SortedGrid<D>::Coordinates SortedGrid<D>::coordinates(std::size_t cell) const {
    Vec<D> x;
    for (int a = 0; a < D; ++a)
        x[a] = sorted_x_[a][cell_start_[cell]];
    const Coord at = cell_of(x);
    Coordinates c;
    for (int a = 0; a < D; ++a)
        c[a] = at[a];
    return c;
}

template <int D>
typename SortedGrid<D>::Range SortedGrid<D>::range_at(const Coordinates& at) const {
    std::uint64_t key = 0;
    for (int a = 0; a < D; ++a) {
        if (at[a] < 0 || at[a] >= std::int64_t(cell_count_[a]))
            return {0, 0};
        key |= spread(a, static_cast<std::uint32_t>(at[a]));
    }
    return cell_range(key);
}

template <int D>
int SortedGrid<D>::neighbour_runs(std::size_t cell, NeighbourRuns& runs) const {
    constexpr int neighbour_cells = D == 2 ? 9 : 27;
    const std::uint32_t first = cell_start_[cell];
    Vec<D> x;
    for (int a = 0; a < D; ++a)
        x[a] = sorted_x_[a][first];
    const Coord centre = cell_of(x);
    // The 3^D surrounding cells' runs, by position in the sorted arrays.
    std::array<std::array<std::uint64_t, 3>, D> part{};
    std::array<int, D> low, high;
    for (int a = 0; a < D; ++a) {
        low[a] = centre[a] > 0 ? 0 : 1;
        high[a] = centre[a] + 1 < cell_count_[a] ? 2 : 1;
        for (int o = low[a]; o <= high[a]; ++o)
            part[a][o] = spread(a, centre[a] + o - 1);
    }
    int count = 0;
    for (int k = 0; k < neighbour_cells; ++k) {
        std::uint64_t key = 0;
        bool inside = true;
        int rest = k;
        for (int a = 0; a < D; ++a) {
            const int o = rest % 3;
            rest /= 3;
            inside = inside && o >= low[a] && o <= high[a];
            key |= inside ? part[a][o] : 0;
        }
        if (!inside)
            continue;
        const Range r = cell_range(key);
        if (r.end > r.begin) {
            int at = count++;
            for (; at > 0 && runs[at - 1].begin > r.begin; --at)
                runs[at] = runs[at - 1];
            runs[at] = r;
        }
    }
    return count;
}

template <int D>
std::size_t SortedGrid<D>::gather_candidates(std::size_t cell, Real r2, Scratch& s) const {
    const std::uint32_t first = cell_start_[cell], last = cell_start_[cell + 1];
    Vec<D> lo(std::numeric_limits<Real>::max()), hi(std::numeric_limits<Real>::lowest());
    // The box around the cell's particles; a NaN or infinity has no neighbour
    // to look for.
    for (std::uint32_t k = first; k < last; ++k)
        for (int a = 0; a < D; ++a) {
            const Real v = sorted_x_[a][k];
            if (std::abs(v) <= std::numeric_limits<Real>::max()) {
                lo[a] = std::min(lo[a], v);
                hi[a] = std::max(hi[a], v);
            }
        }

    NeighbourRuns ranges;
    const int range_count = neighbour_runs(cell, ranges);
    std::size_t total = 0;
    for (int k = 0; k < range_count; ++k)
        total += ranges[k].end - ranges[k].begin;
    if (s.keyed.size() < total) {
        // With headroom (sph/headroom.hpp): a cell's candidates grow a few
        // at a time as a fluid settles, and each growth would allocate.
        const std::size_t grown = total + total / 4;
        s.keyed.resize(grown);
        s.merged.resize(grown); // sort_by_index's
        s.run_ends.reserve(grown + 1);
        for (int a = 0; a < D; ++a)
            s.x[a].resize(grown);
        s.index.resize(grown);
        s.distance2.resize(grown);
    }

    // Only candidates closer than the radius to the box around the cell's
    // particles can be anyone's neighbour (a quarter of a lattice's are not).
    // Rounding is monotonic, so this distance, summed like glm::dot, is never
    // above a computed particle distance: the test drops no pair.
    std::size_t count = 0;
    Real* gap2 = s.distance2.data();
    for (int k = 0; k < range_count; ++k) {
        const std::uint32_t begin = ranges[k].begin, length = ranges[k].end - begin;
        if constexpr (D == 2)
            squared_gaps(length, sorted_x_[0].data() + begin, sorted_x_[1].data() + begin, lo[0],
                         hi[0], lo[1], hi[1], gap2);
        else
            squared_gaps(length, sorted_x_[0].data() + begin, sorted_x_[1].data() + begin,
                         sorted_x_[2].data() + begin, lo[0], hi[0], lo[1], hi[1], lo[2], hi[2],
                         gap2);
        for (std::uint32_t m = 0; m < length; ++m) {
            s.keyed[count] = std::uint64_t(order_[begin + m]) << 32 | (begin + m);
            count += gap2[m] < r2;
        }
    }
    // By index, so that every row comes out sorted; already so when the
    // particle arrays are stored in cell order.
    sort_by_index(count, s);
    for (std::size_t m = 0; m < count; ++m) {
        const auto j = static_cast<std::uint32_t>(s.keyed[m]);
        s.index[m] = static_cast<std::uint32_t>(s.keyed[m] >> 32);
        for (int a = 0; a < D; ++a)
            s.x[a][m] = sorted_x_[a][j];
    }
    return count;
}

// Each cell's particles come in ascending index (the cell sorts are stable),
// and between the spatial sorts of the particle arrays neighbouring cells
// hold mostly ascending ranges: the candidates are a few ascending runs.
// Merging them pairwise costs n log(runs); std::sort, which cannot see them,
// cost n log n and 23% of the search on a 3D dam break (measured, perf).
// Keys are distinct, so the result is std::sort's, bit for bit.
template <int D>
void SortedGrid<D>::sort_by_index(std::size_t count, Scratch& s) {
    s.run_ends.clear();
    for (std::size_t m = 1; m < count; ++m)
        if (s.keyed[m] < s.keyed[m - 1])
            s.run_ends.push_back(static_cast<std::uint32_t>(m));
    if (s.run_ends.empty())
        return;
    s.run_ends.push_back(static_cast<std::uint32_t>(count));
    std::uint64_t* from = s.keyed.data();
    std::uint64_t* to = s.merged.data();
    while (s.run_ends.size() > 1) {
        // Runs k and k + 1 into one; an odd last run is copied as it is.
        std::size_t begin = 0, kept = 0;
        for (std::size_t k = 0; k < s.run_ends.size(); k += 2) {
            const std::size_t middle = s.run_ends[k];
            const std::size_t end = k + 1 < s.run_ends.size() ? s.run_ends[k + 1] : middle;
            std::merge(from + begin, from + middle, from + middle, from + end, to + begin);
            s.run_ends[kept++] = static_cast<std::uint32_t>(end);
            begin = end;
        }
        s.run_ends.resize(kept);
        std::swap(from, to);
    }
    if (from != s.keyed.data())
        std::copy(from, from + count, s.keyed.data());
}

template <int D>
SPHCLIP_CLONED void SortedGrid<D>::list_neighbours(Real radius, NeighbourList& out) {
    const std::size_t n = order_.size();
    const std::size_t cells = cell_start_.size() - 1;
    const Real r2 = radius * radius;
    const std::size_t rows_begin = this->rows_begin_, rows_end = this->rows_end_;
    scratch_.resize(std::max<std::size_t>(scratch_.size(), omp_get_max_threads()));
    row_offset_.resize(n);
    row_thread_.resize(n);
    out.start.resize(n + 1);

    // Rows go to per-thread buffers, in whatever order the cells are handed
    // out; each particle's row is then copied to its place. One distance pass,
    // and the result does not depend on the thread count.
#pragma omp parallel
    {
        const int thread = omp_get_thread_num();
        Scratch& s = scratch_[thread];
        std::size_t used = 0;
#pragma omp for schedule(dynamic, 16)
        for (std::size_t c = 0; c < cells; ++c) {
            const std::uint32_t first = cell_start_[c], last = cell_start_[c + 1];
            // Rows not wanted (want_rows) stay empty; a cell with none wanted
            // gathers nothing.
            bool wanted = false;
            for (std::uint32_t k = first; k < last && !wanted; ++k)
                wanted = order_[k] >= rows_begin && order_[k] < rows_end;
            if (!wanted) {
                for (std::uint32_t k = first; k < last; ++k) {
                    row_offset_[order_[k]] = static_cast<std::uint32_t>(used);
                    row_thread_[order_[k]] = static_cast<std::uint16_t>(thread);
                    out.start[order_[k] + 1] = 0;
                }
                continue;
            }
            // Gathered once per cell, so each particle runs one long loop.
            const std::size_t candidates = gather_candidates(c, r2, s);
            for (std::uint32_t k = first; k < last; ++k) {
                if (order_[k] < rows_begin || order_[k] >= rows_end) {
                    row_offset_[order_[k]] = static_cast<std::uint32_t>(used);
                    row_thread_[order_[k]] = static_cast<std::uint16_t>(thread);
                    out.start[order_[k] + 1] = 0;
                    continue;
                }
                if constexpr (D == 2)
                    squared_distances(candidates, s.x[0].data(), s.x[1].data(), sorted_x_[0][k],
                                      sorted_x_[1][k], s.distance2.data());
                else
                    squared_distances(candidates, s.x[0].data(), s.x[1].data(), s.x[2].data(),
                                      sorted_x_[0][k], sorted_x_[1][k], sorted_x_[2][k],
                                      s.distance2.data());
                if (s.rows.size() < used + candidates)
                    s.rows.resize(std::max(2 * s.rows.size(), used + candidates));
                const std::uint32_t self = order_[k];
                const std::uint32_t found = select_neighbours(
                    candidates, s.distance2.data(), s.index.data(), r2, self, s.rows.data() + used);
                row_offset_[self] = static_cast<std::uint32_t>(used);
                row_thread_[self] = static_cast<std::uint16_t>(thread);
                out.start[self + 1] = found;
                used += found;
            }
        }
    }

    out.start[0] = 0;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        total += out.start[i + 1];
        out.start[i + 1] = static_cast<std::uint32_t>(total);
    }
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw std::overflow_error("sorted_grid: more than 2^32 neighbour pairs");
    out.size_for(total);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
        std::copy_n(scratch_[row_thread_[i]].rows.data() + row_offset_[i],
                    out.start[i + 1] - out.start[i], out.index.data() + out.start[i]);
}

template <int D>
bool SortedGrid<D>::sorted_in_place(std::span<const Vec<D>> positions, Real radius) {
    const bool candidate = sorted_for_order_ && radius == sorted_radius_ &&
                           positions.size() == order_.size() && !within_ && !outside_;
    sorted_for_order_ = false;
    if (!candidate)
        return false;
    // Sorted already when each position is the sorted copy's at its index:
    // a sort would then give the identity order and this same grid, bit for
    // bit (the cells' runs, their particles by index). A NaN differs from
    // itself, and sorts again.
    const std::size_t n = positions.size();
    std::size_t differing = 0;
#pragma omp parallel for schedule(static) reduction(+ : differing)
    for (std::size_t k = 0; k < n; ++k)
        for (int a = 0; a < D; ++a)
            differing += positions[k][a] != sorted_x_[a][k];
    if (differing > 0)
        return false;
    std::iota(order_.begin(), order_.end(), 0u);
    return true;
}

template <int D>
void SortedGrid<D>::find(std::span<const Vec<D>> positions, Real radius, NeighbourList& out) {
    const std::size_t n = positions.size();
    if (n >= std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("sorted_grid: more than 2^32 particles");
    timings_ = {};
    if (n == 0 || !(radius > 0)) {
        // Nobody is strictly closer than a radius of zero.
        out.start.assign(n + 1, 0);
        out.size_for(0);
        order_.resize(n);
        std::iota(order_.begin(), order_.end(), 0u);
        cell_start_.assign(1, 0);
        hashed_ = false;
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    if (!sorted_in_place(positions, radius))
        sort_into_cells(positions, radius);
    timings_.build_seconds = seconds_since(start);
    const auto query = std::chrono::steady_clock::now();
    list_neighbours(radius, out);
    timings_.query_seconds = seconds_since(query);
}

template <int D>
std::span<const std::uint32_t> SortedGrid<D>::cell_order(std::span<const Vec<D>> positions,
                                                         Real radius) {
    if (positions.size() >= std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("sorted_grid: more than 2^32 particles");
    if (positions.empty() || !(radius > 0)) {
        order_.resize(positions.size());
        std::iota(order_.begin(), order_.end(), 0u);
        cell_start_.assign(1, 0);
    } else {
        sort_into_cells(positions, radius);
        sorted_for_order_ = !within_ && !outside_;
        sorted_radius_ = radius;
    }
    return order_;
}

template <int D>
std::span<const std::uint32_t> SortedGrid<D>::cell_order(std::span<const Vec<D>> positions,
                                                         Real radius, const Box<D>& within) {
    within_ = &within;
    try {
        cell_order(positions, radius);
    } catch (...) {
        within_ = nullptr;
        throw;
    }
    within_ = nullptr;
    return order_;
}

template <int D>
std::span<const std::uint32_t> SortedGrid<D>::cell_order(std::span<const Vec<D>> positions,
                                                         Real radius, const Box<D>& within,
                                                         const Box<D>& outside) {
    outside_ = &outside;
    try {
        cell_order(positions, radius, within);
    } catch (...) {
        outside_ = nullptr;
        throw;
    }
    outside_ = nullptr;
    return order_;
}

template Box<2> finite_bounds<2>(std::span<const Vec<2>>);
template Box<3> finite_bounds<3>(std::span<const Vec<3>>);
template class SortedGrid<2>;
template class SortedGrid<3>;

} // namespace sph
