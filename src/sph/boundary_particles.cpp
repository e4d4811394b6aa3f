#include "sph/boundary_particles.hpp"

#include "sph/lattice.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

namespace sph {

template <int D>
typename BoundaryParticles<D>::Cell BoundaryParticles<D>::cell_of(const Vec<D>& x) const {
    // Clamped before the conversion: a point far outside (or not finite)
    // lands outside the grid instead of overflowing.
    Cell c;
    for (int a = 0; a < D; ++a) {
        const Real k = std::floor((x[a] - origin_[a]) / h_);
        c[a] = k >= -2 && k <= Real(cells_[a] + 1) ? static_cast<std::int64_t>(k) : -2;
    }
    return c;
}

template <int D>
std::size_t BoundaryParticles<D>::cell_index(const Cell& c) const {
    std::size_t index = 0;
    for (int a = D - 1; a >= 0; --a)
        index = index * static_cast<std::size_t>(cells_[a]) + static_cast<std::size_t>(c[a]);
    return index;
}

template <int D>
template <class Visit>
void BoundaryParticles<D>::for_each_near(const Vec<D>& x, Visit&& visit) const {
    const Cell centre = cell_of(x);
    Cell lo, hi;
    for (int a = 0; a < D; ++a) {
        lo[a] = std::max<std::int64_t>(centre[a] - 1, 0);
        hi[a] = std::min<std::int64_t>(centre[a] + 1, cells_[a] - 1);
        if (lo[a] > hi[a])
            return; // far outside the walls' box
    }
    const Real r2 = h_ * h_;
    auto visit_cell = [&](const Cell& c) {
        const std::size_t k = cell_index(c);
        for (std::uint32_t b = cell_start_[k]; b < cell_start_[k + 1]; ++b)
            if (squared_length<D>(x - positions_[b]) < r2)
                visit(b);
    };
    if constexpr (D == 2) {
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
            for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                visit_cell(Cell(i, j));
    } else {
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
            for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
                for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
                    visit_cell(Cell(i, j, k));
    }
}

template <int D>
std::vector<std::uint32_t> BoundaryParticles<D>::build_grid(std::vector<Vec<D>> positions) {
    const std::size_t n = positions.size();
    if (n == 0) {
        cell_start_.assign(2, 0);
        for (int a = 0; a < D; ++a)
            cells_[a] = 1;
        return {};
    }
    Vec<D> lo = positions[0], hi = positions[0];
    for (const Vec<D>& x : positions) {
        lo = glm::min(lo, x);
        hi = glm::max(hi, x);
    }
    origin_ = lo;
    std::size_t total = 1;
    for (int a = 0; a < D; ++a) {
        cells_[a] = static_cast<std::int64_t>(std::floor((hi[a] - lo[a]) / h_)) + 1;
        total *= static_cast<std::size_t>(cells_[a]);
    }
    // Counting sort by cell: positions end up grouped cell by cell.
    std::vector<std::size_t> cell(n);
    cell_start_.assign(total + 1, 0);
    for (std::size_t b = 0; b < n; ++b) {
        cell[b] = cell_index(cell_of(positions[b]));
        ++cell_start_[cell[b] + 1];
    }
    std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
    std::vector<std::uint32_t> next(cell_start_.begin(), cell_start_.end() - 1);
    std::vector<std::uint32_t> destination(n);
    positions_.resize(n);
    for (std::size_t b = 0; b < n; ++b) {
        destination[b] = next[cell[b]]++;
        positions_[destination[b]] = positions[b];
    }
    return destination;
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, Real h, Real volume)
    : h_(h) {
    build_grid(std::move(positions));
    volumes_.assign(positions_.size(), volume);
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, std::vector<Real> volumes,
                                        Real h)
    : h_(h) {
    assert(positions.size() == volumes.size());
    const std::vector<std::uint32_t> destination = build_grid(std::move(positions));
    volumes_.resize(volumes.size());
    for (std::size_t b = 0; b < volumes.size(); ++b)
        volumes_[destination[b]] = volumes[b];
}

template <int D>
BoundaryParticles<D>::BoundaryParticles(std::vector<Vec<D>> positions, Real h, KernelKind kernel)
    : h_(h) {
    build_grid(std::move(positions));
    const std::size_t n = positions_.size();
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
BoundaryParticles<D> BoundaryParticles<D>::box_walls(const Box<D>& domain, Real spacing, Real h,
                                                     Real lattice_volume) {
    const auto layers = static_cast<std::int64_t>(std::ceil(h / spacing));
    glm::vec<D, std::int64_t, glm::defaultp> inside;
    for (int a = 0; a < D; ++a)
        inside[a] = static_cast<std::int64_t>(lattice_count(domain.min[a], domain.max[a], spacing));
    std::vector<Vec<D>> positions;
    auto add_if_outside = [&](const glm::vec<D, std::int64_t, glm::defaultp>& k) {
        bool outside = false;
        Vec<D> x;
        for (int a = 0; a < D; ++a) {
            outside = outside || k[a] < 0 || k[a] >= inside[a];
            x[a] = domain.min[a] + (Real(k[a]) + Real(0.5)) * spacing;
        }
        if (outside)
            positions.push_back(x);
    };
    if constexpr (D == 2) {
        for (std::int64_t j = -layers; j < inside[1] + layers; ++j)
            for (std::int64_t i = -layers; i < inside[0] + layers; ++i)
                add_if_outside({i, j});
    } else {
        for (std::int64_t k = -layers; k < inside[2] + layers; ++k)
            for (std::int64_t j = -layers; j < inside[1] + layers; ++j) {
                // Interior rows: only the first and last layers are outside.
                const bool shell_row = k < 0 || k >= inside[2] || j < 0 || j >= inside[1];
                for (std::int64_t i = -layers; i < inside[0] + layers; ++i) {
                    if (!shell_row && i == 0)
                        i = inside[0]; // skip the box's interior
                    add_if_outside({i, j, k});
                }
            }
    }
    return BoundaryParticles(std::move(positions), h, lattice_volume);
}

template <int D>
void BoundaryParticles<D>::find_neighbours(std::span<const Vec<D>> query,
                                           NeighbourList& out) const {
    const std::size_t n = query.size();
    out.start.resize(n + 1);
    out.start[0] = 0;
    if (positions_.empty()) {
        std::fill(out.start.begin(), out.start.end(), 0);
        out.index.clear();
        return;
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t count = 0;
        for_each_near(query[i], [&](std::uint32_t) { ++count; });
        out.start[i + 1] = count;
    }
    for (std::size_t i = 0; i < n; ++i)
        out.start[i + 1] += out.start[i];
    if (out.index.capacity() < out.start[n])
        out.index.reserve(out.start[n] + out.start[n] / 4);
    out.index.resize(out.start[n]);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t* row = out.index.data() + out.start[i];
        for_each_near(query[i], [&](std::uint32_t b) { *row++ = b; });
    }
}

template class BoundaryParticles<2>;
template class BoundaryParticles<3>;

} // namespace sph
