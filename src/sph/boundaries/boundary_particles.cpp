#include "sph/boundaries/boundary_particles.hpp"

#include "sph/assert.hpp"
#include "sph/headroom.hpp"
#include "sph/lattice.hpp"
#include "sph/neighbours/distance_filter.hpp"
#include "sph/vector_clones.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace sph {

template <int D>
typename BoundaryParticles<D>::Cell BoundaryParticles<D>::cell_of(const Grid& grid,
                                                                  const Vec<D>& x) const {
    // Clamped before the conversion: a point far outside (or not finite)
    // lands outside the grid instead of overflowing.
    Cell c;
    for (int a = 0; a < D; ++a) {
        const Real k = std::floor((x[a] - grid.origin[a]) / h_) - Real(grid.first[a]);
        c[a] = k >= -2 && k <= Real(grid.cells[a] + 1) ? static_cast<std::int64_t>(k) : -2;
    }
    return c;
}

template <int D>
std::size_t BoundaryParticles<D>::cell_index(const Grid& grid, const Cell& c) {
    std::size_t index = 0;
    for (int a = D - 1; a >= 0; --a)
        index = index * static_cast<std::size_t>(grid.cells[a]) + static_cast<std::size_t>(c[a]);
    return index;
}

template <int D>
template <class VisitRow>
void BoundaryParticles<D>::for_each_row_in(const Grid& grid, const Vec<D>& x,
                                           VisitRow&& visit_row) const {
    const Cell centre = cell_of(grid, x);
    if (!grid.near_any.empty()) {
        bool inside = true;
        for (int a = 0; a < D; ++a)
            inside = inside && centre[a] >= 0 && centre[a] < grid.cells[a];
        if (inside && !grid.near_any[cell_index(grid, centre)])
            return;
    }
    Cell lo, hi;
    for (int a = 0; a < D; ++a) {
        lo[a] = std::max<std::int64_t>(centre[a] - 1, 0);
        hi[a] = std::min<std::int64_t>(centre[a] + 1, grid.cells[a] - 1);
        if (lo[a] > hi[a])
            return; // far outside the grid's box
    }
    for_each_row_between(grid, lo, hi, visit_row);
}

template <int D>
template <class VisitRow>
void BoundaryParticles<D>::for_each_row_between(const Grid& grid, const Cell& lo, const Cell& hi,
                                                VisitRow&& visit_row) {
    // The cells along x are consecutive in the grid (cell_index), so the
    // lo..hi cells of a row are one range of entries, in the cells' order.
    auto visit_cells = [&](Cell first, Cell last) {
        visit_row(grid.cell_start[cell_index(grid, first)],
                  grid.cell_start[cell_index(grid, last) + 1]);
    };
    if constexpr (D == 2) {
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            visit_cells(Cell(lo[0], j), Cell(hi[0], j));
    } else {
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                visit_cells(Cell(lo[0], j, k), Cell(hi[0], j, k));
    }
}

template <int D>
template <bool Moving, class Visit>
void BoundaryParticles<D>::for_each_in(const Grid& grid, const Vec<D>& x, Visit&& visit) const {
    const Real r2 = h_ * h_;
    for_each_row_in(grid, x, [&](std::uint32_t begin, std::uint32_t end) {
        for (std::uint32_t e = begin; e < end; ++e) {
            const std::uint32_t b = Moving ? moving_order_[e] : e;
            if (squared_length<D>(x - positions_[b]) < r2)
                visit(b);
        }
    });
}

template <int D>
template <bool Moving>
std::size_t BoundaryParticles<D>::collect_in(const Grid& grid, const Vec<D>& x,
                                             std::vector<std::uint32_t>& out,
                                             std::size_t count) const {
    const Real r2 = h_ * h_;
    for_each_row_in(grid, x, [&](std::uint32_t begin, std::uint32_t end) {
        if (out.size() < count + (end - begin))
            out.resize(std::max(2 * out.size(), count + (end - begin)));
        // Every candidate written, the count moved past the near ones: no
        // branch to mispredict (about a third of the candidates are near).
        std::uint32_t* const to = out.data();
        for (std::uint32_t e = begin; e < end; ++e) {
            const std::uint32_t b = Moving ? moving_order_[e] : e;
            to[count] = b;
            count += squared_length<D>(x - positions_[b]) < r2;
        }
    });
    return count;
}

template <int D>
std::size_t BoundaryParticles<D>::collect_static(const Vec<D>& x, std::vector<std::uint32_t>& out,
                                                 std::vector<Real>& distance2,
                                                 std::size_t count) const {
    const Real r2 = h_ * h_;
    constexpr std::uint32_t nobody = std::numeric_limits<std::uint32_t>::max();
    for_each_row_in(grid_, x, [&](std::uint32_t begin, std::uint32_t end) {
        const std::size_t length = end - begin;
        if (out.size() < count + length)
            out.resize(std::max(2 * out.size(), count + length));
        if (distance2.size() < length)
            distance2.resize(2 * length);
        if constexpr (D == 2)
            squared_distances(length, static_x_[0].data() + begin, static_x_[1].data() + begin,
                              x[0], x[1], distance2.data());
        else
            squared_distances(length, static_x_[0].data() + begin, static_x_[1].data() + begin,
                              static_x_[2].data() + begin, x[0], x[1], x[2], distance2.data());
        count += select_neighbours(length, distance2.data(), static_index_.data() + begin, r2,
                                   nobody, out.data() + count);
    });
    return count;
}

template <int D>
template <class Visit>
void BoundaryParticles<D>::for_each_near(const Vec<D>& x, Visit&& visit) const {
    for_each_in<false>(grid_, x, visit);
    if (has_moving())
        for_each_in<true>(moving_grid_, x, visit);
}

namespace {

template <int D>
Box<D> bounding_box(std::span<const Vec<D>> points) {
    Box<D> box{points[0], points[0]};
    for (const Vec<D>& x : points) {
        box.min = glm::min(box.min, x);
        box.max = glm::max(box.max, x);
    }
    return box;
}

} // namespace

template <int D>
void BoundaryParticles<D>::within(const Box<D>& box, std::vector<std::uint32_t>& out) const {
    const auto inside = [&](const Vec<D>& x) {
        bool in = true;
        for (int a = 0; a < D; ++a)
            in = in && x[a] >= box.min[a] && x[a] <= box.max[a];
        return in;
    };
    // The static particles lie cell by cell in cell_index's order (x
    // fastest), so rows of cells visited in that order give them in
    // increasing order.
    const Grid& grid = grid_;
    Cell lo(0), hi(0); // (GCC 12 cannot tell the loop below sets them)
    bool any = moving_begin_ > 0;
    for (int a = 0; a < D; ++a) {
        // floor as in cell_of, clamped to the grid before the conversion
        // (a NaN to -1: no cell).
        const auto cell = [&](Real x) {
            const Real k = std::floor((x - grid.origin[a]) / h_) - Real(grid.first[a]);
            return k > Real(-1)
                       ? (k < Real(grid.cells[a]) ? static_cast<std::int64_t>(k) : grid.cells[a])
                       : std::int64_t{-1};
        };
        lo[a] = std::max<std::int64_t>(cell(box.min[a]), 0);
        hi[a] = std::min<std::int64_t>(cell(box.max[a]), grid.cells[a] - 1);
        any = any && lo[a] <= hi[a];
    }
    // By every thread (SelectInOrder): one alone took 1.4% of the 3D dam
    // break's step, at 97k particles, while the others waited.
    within_.clear();
    if (any)
        for_each_row_between(
            grid, lo, hi, [&](std::uint32_t begin, std::uint32_t end) { within_.add(begin, end); });
    within_.add(static_cast<std::uint32_t>(moving_begin_),
                static_cast<std::uint32_t>(positions_.size()));
    within_.append_to(out, [&](std::uint32_t b) { return inside(positions_[b]); });
}

template <int D>
std::size_t BoundaryParticles<D>::fit_grid(Grid& grid, std::span<const Vec<D>> points) const {
    const Box<D> box = bounding_box<D>(points);
    grid.origin = box.min;
    grid.first = Cell(0);
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) {
        grid.cells[a] = static_cast<std::int64_t>(std::floor((box.max[a] - box.min[a]) / h_)) + 1;
        total *= static_cast<std::size_t>(grid.cells[a]);
    }
    return total;
}

template <int D>
void BoundaryParticles<D>::mark_near_cells(Grid& grid) {
    grid.near_any.assign(grid.cell_start.size() - 1, 0);
    auto mark_around = [&](const Cell& c) {
        Cell lo, hi;
        for (int a = 0; a < D; ++a) {
            lo[a] = std::max<std::int64_t>(c[a] - 1, 0);
            hi[a] = std::min<std::int64_t>(c[a] + 1, grid.cells[a] - 1);
        }
        if constexpr (D == 2) {
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                    grid.near_any[cell_index(grid, Cell(i, j))] = 1;
        } else {
            for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
                for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                        grid.near_any[cell_index(grid, Cell(i, j, k))] = 1;
        }
    };
    Cell c(0);
    for (std::size_t k = 0; k + 1 < grid.cell_start.size(); ++k) {
        if (grid.cell_start[k + 1] > grid.cell_start[k])
            mark_around(c);
        // The next cell, x fastest (cell_index's order).
        for (int a = 0; a < D; ++a) {
            if (++c[a] < grid.cells[a])
                break;
            c[a] = 0;
        }
    }
}

template <int D>
std::vector<std::uint32_t> BoundaryParticles<D>::build_grid(std::vector<Vec<D>> positions,
                                                            const Box<D>* whole) {
    const std::size_t n = positions.size();
    if (whole)
        bounds_ = *whole;
    else if (n > 0)
        bounds_ = bounding_box<D>(positions);
    if (n == 0) {
        for (std::vector<Real>& component : static_x_)
            component.clear();
        static_index_.clear();
        grid_.cell_start.assign(2, 0);
        for (int a = 0; a < D; ++a)
            grid_.cells[a] = 1;
        return {};
    }
    std::size_t total = fit_grid(grid_, positions);
    if (whole) {
        // The whole set's grid, of which only the cells from the first to
        // the last that hold one of these particles are kept.
        grid_.origin = whole->min;
        Cell lo(std::numeric_limits<std::int64_t>::max()),
            hi(std::numeric_limits<std::int64_t>::min());
        for (const Vec<D>& x : positions)
            for (int a = 0; a < D; ++a) {
                const auto k = static_cast<std::int64_t>(std::floor((x[a] - whole->min[a]) / h_));
                lo[a] = std::min(lo[a], k);
                hi[a] = std::max(hi[a], k);
            }
        grid_.first = lo;
        total = 1;
        for (int a = 0; a < D; ++a) {
            grid_.cells[a] = hi[a] - lo[a] + 1;
            total *= static_cast<std::size_t>(grid_.cells[a]);
        }
    }
    // Counting sort by cell: positions end up grouped cell by cell.
    std::vector<std::size_t> cell(n);
    std::vector<std::uint32_t>& cell_start = grid_.cell_start;
    cell_start.assign(total + 1, 0);
    for (std::size_t b = 0; b < n; ++b) {
        cell[b] = cell_index(grid_, cell_of(grid_, positions[b]));
        ++cell_start[cell[b] + 1];
    }
    std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
    std::vector<std::uint32_t> next(cell_start.begin(), cell_start.end() - 1);
    std::vector<std::uint32_t> destination(n);
    positions_.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
        destination[b] = next[cell[b]]++;
        positions_[destination[b]] = positions[b];
    }
    for (int a = 0; a < D; ++a) {
        static_x_[a].resize(n);
        for (std::size_t b = 0; b < n; ++b)
            static_x_[a][b] = positions_[b][a];
    }
    static_index_.resize(n);
    std::iota(static_index_.begin(), static_index_.end(), 0u);
    mark_near_cells(grid_);
    return destination;
}

template <int D>
void BoundaryParticles<D>::add_moving(std::vector<Vec<D>> rest, std::vector<Real> volumes,
                                      std::vector<std::uint32_t> group) {
    SPHCLIP_ASSERT(rest.size() == volumes.size() && rest.size() == group.size());
    SPHCLIP_ASSERT(!has_moving()); // one set of moving particles
    moving_begin_ = positions_.size();
    positions_.insert(positions_.end(), rest.begin(), rest.end());
    volumes_.insert(volumes_.end(), volumes.begin(), volumes.end());
    rest_ = std::move(rest);
    group_ = std::move(group);
    velocities_.resize(positions_.size(), Vec<D>(0));
    refresh_moving_grid();
}

template <int D>
void BoundaryParticles<D>::refresh_moving_grid() {
    const std::span<const Vec<D>> moving =
        std::span<const Vec<D>>(positions_).subspan(moving_begin_);
    const std::size_t n = moving.size();
    if (n == 0)
        return;
    // Counting sort of the moving particles' indices by cell; their data stay
    // in place, in the order their motion writes them. Sizes settle after the
    // first call: no allocation per step.
    const std::size_t total = fit_grid(moving_grid_, moving);
    std::vector<std::uint32_t>& cell_start = moving_grid_.cell_start;
    cell_start.assign(total + 1, 0);
    moving_cell_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        moving_cell_[k] = cell_index(moving_grid_, cell_of(moving_grid_, moving[k]));
        ++cell_start[moving_cell_[k] + 1];
    }
    std::partial_sum(cell_start.begin(), cell_start.end(), cell_start.begin());
    moving_next_.assign(cell_start.begin(), cell_start.end() - 1);
    moving_order_.resize(n);
    for (std::size_t k = 0; k < n; ++k)
        moving_order_[moving_next_[moving_cell_[k]]++] =
            static_cast<std::uint32_t>(moving_begin_ + k);
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, Real h, Real volume)
    : h_(h) {
    build_grid(std::move(positions));
    volumes_.assign(positions_.size(), volume);
    moving_begin_ = positions_.size();
    velocities_.assign(positions_.size(), Vec<D>(0));
}

template <int D>
void BoundaryParticles<D>::take_static(std::vector<Vec<D>> positions, std::vector<Real> volumes,
                                       const Box<D>* whole) {
    SPHCLIP_ASSERT(positions.size() == volumes.size());
    const std::vector<std::uint32_t> destination = build_grid(std::move(positions), whole);
    volumes_.resize(volumes.size());
    for (std::size_t b = 0; b < volumes.size(); ++b)
        volumes_[destination[b]] = volumes[b];
    moving_begin_ = positions_.size();
    velocities_.assign(positions_.size(), Vec<D>(0));
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes,
                                        Real h)
    : h_(h) {
    take_static(std::move(positions), std::move(volumes), nullptr);
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes,
                                        Real h, const Box<D>& whole)
    : h_(h) {
    take_static(std::move(positions), std::move(volumes), &whole);
}

template <int D>
void BoundaryParticles<D>::replace_static(BoundaryParticles&& other) {
    SPHCLIP_ASSERT(!other.has_moving());
    const auto moving = std::ptrdiff_t(moving_begin_);
    std::vector<Vec<D>> positions(positions_.begin() + moving, positions_.end());
    std::vector<Vec<D>> velocities(velocities_.begin() + moving, velocities_.end());
    std::vector<Real> volumes(volumes_.begin() + moving, volumes_.end());
    positions_ = std::move(other.positions_);
    volumes_ = std::move(other.volumes_);
    velocities_ = std::move(other.velocities_);
    grid_ = std::move(other.grid_);
    static_x_ = std::move(other.static_x_);
    static_index_ = std::move(other.static_index_);
    bounds_ = other.bounds_;
    moving_begin_ = positions_.size();
    positions_.insert(positions_.end(), positions.begin(), positions.end());
    volumes_.insert(volumes_.end(), volumes.begin(), volumes.end());
    velocities_.insert(velocities_.end(), velocities.begin(), velocities.end());
    // The static ones' memory given back, as a process's share of a large
    // tank's walls is what it holds in place of all of them.
    positions_.shrink_to_fit();
    volumes_.shrink_to_fit();
    velocities_.shrink_to_fit();
    refresh_moving_grid();
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, Real h, KernelKind kernel)
    : h_(h) {
    build_grid(std::move(positions));
    const std::size_t n = positions_.size();
    moving_begin_ = n;
    velocities_.assign(n, Vec<D>(0));
    // V_b = 1 / sum_k W_bk, the particle itself included (Akinci et al. 2012, eq. 4).
    volumes_.resize(n);
    with_kernel<D>(kernel, h, [&](const auto& W) {
#pragma omp parallel for schedule(static)
        for (std::size_t b = 0; b < n; ++b) {
            Real sum = 0;
            for_each_near(positions_[b], [&](std::uint32_t k) {
                sum += W.W(std::sqrt(squared_length<D>(positions_[b] - positions_[k])));
            });
            volumes_[b] = 1 / sum;
        }
    });
}

template <int D>
std::vector<Vec<D>> BoundaryParticles<D>::box_wall_sites(const Box<D>& domain, Real spacing, Real h,
                                                         const Box<D>* region, Box<D>& bounds) {
    using Index = glm::vec<D, std::int64_t, glm::defaultp>;
    const auto layers = static_cast<std::int64_t>(std::ceil(h / spacing));
    Index inside, first, last; // sites first..last along each axis
    bool none = false;         // the region holds no site
    auto site = [&](int a, std::int64_t k) {
        return domain.min[a] + (Real(k) + Real(0.5)) * spacing;
    };
    for (int a = 0; a < D; ++a) {
        inside[a] = static_cast<std::int64_t>(lattice_count(domain.min[a], domain.max[a], spacing));
        first[a] = -layers;
        last[a] = inside[a] + layers - 1;
        bounds.min[a] = site(a, first[a]);
        bounds.max[a] = site(a, last[a]);
        if (region) {
            // The sites within the region's span, and one more each side
            // for rounding: the test below is exact.
            const Real lo = std::floor((region->min[a] - domain.min[a]) / spacing - Real(0.5));
            const Real hi = std::ceil((region->max[a] - domain.min[a]) / spacing - Real(0.5));
            if (!(lo <= hi) || lo > Real(last[a]) || hi < Real(first[a])) {
                none = true;
                continue;
            }
            if (lo - 1 > Real(first[a]))
                first[a] = std::int64_t(lo) - 1;
            if (hi + 1 < Real(last[a]))
                last[a] = std::int64_t(hi) + 1;
        }
    }
    std::vector<Vec<D>> positions;
    if (none)
        return positions;
    auto add_if_outside = [&](const Index& k) {
        bool outside = false, kept = true;
        Vec<D> x;
        for (int a = 0; a < D; ++a) {
            outside = outside || k[a] < 0 || k[a] >= inside[a];
            x[a] = site(a, k[a]);
            kept = kept && (!region || (x[a] >= region->min[a] && x[a] <= region->max[a]));
        }
        if (outside && kept)
            positions.push_back(x);
    };
    if constexpr (D == 2) {
        for (std::int64_t j = first[1]; j <= last[1]; ++j)
            for (std::int64_t i = first[0]; i <= last[0]; ++i)
                add_if_outside({i, j});
    } else {
        for (std::int64_t k = first[2]; k <= last[2]; ++k)
            for (std::int64_t j = first[1]; j <= last[1]; ++j) {
                // Interior rows: only the first and last layers are outside.
                const bool shell_row = k < 0 || k >= inside[2] || j < 0 || j >= inside[1];
                for (std::int64_t i = first[0]; i <= last[0]; ++i) {
                    if (!shell_row && i >= 0 && i < inside[0])
                        i = inside[0]; // skip the box's interior
                    if (i <= last[0])
                        add_if_outside({i, j, k});
                }
            }
    }
    return positions;
}

template <int D>
BoundaryParticles<D> BoundaryParticles<D>::box_walls(const Box<D>& domain, Real spacing, Real h,
                                                     Real lattice_volume) {
    Box<D> bounds;
    return BoundaryParticles(box_wall_sites(domain, spacing, h, nullptr, bounds), h,
                             lattice_volume);
}

template <int D>
SPHCLIP_CLONED void BoundaryParticles<D>::find_neighbours(std::span<const Vec<D>> query,
                                                          NeighbourList& out) const {
    const std::size_t n = query.size();
    out.start.resize(n + 1);
    out.start[0] = 0;
    if (positions_.empty()) {
        std::fill(out.start.begin(), out.start.end(), 0);
        out.size_for(0);
        return;
    }
    // One walk over the cells, not two (one to count, one to fill): each
    // block of rows lists its walls in a buffer of its own, and the buffers
    // are then copied in order (the same list for any thread count).
    constexpr std::size_t block = 256;
    const std::size_t blocks = (n + block - 1) / block;
    if (block_rows_.size() < blocks) {
        block_rows_.resize(blocks);
        block_counts_.resize(blocks);
        block_distance2_.resize(blocks);
    }
#pragma omp parallel for schedule(dynamic, 1)
    for (std::size_t k = 0; k < blocks; ++k) {
        // rows holds the block's lists in its first `count` entries, and
        // room beyond (collect_in writes candidates there).
        std::vector<std::uint32_t>& rows = block_rows_[k];
        std::size_t count = 0;
        for (std::size_t i = k * block, end = std::min(n, i + block); i < end; ++i) {
            const std::size_t before = count;
            count = collect_static(query[i], rows, block_distance2_[k], count);
            if (has_moving())
                count = collect_in<true>(moving_grid_, query[i], rows, count);
            out.start[i + 1] = static_cast<std::uint32_t>(count - before);
        }
        block_counts_[k] = count;
    }
    for (std::size_t i = 0; i < n; ++i)
        out.start[i + 1] += out.start[i];
    out.size_for(out.start[n]);
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < blocks; ++k)
        std::copy_n(block_rows_[k].begin(), block_counts_[k],
                    out.index.begin() + std::ptrdiff_t(out.start[k * block]));
}

template class BoundaryParticles<2>;
template class BoundaryParticles<3>;

} // namespace sph
