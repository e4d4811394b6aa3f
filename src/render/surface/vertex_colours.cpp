#include "render/surface/vertex_colours.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace sph {

namespace {

// The particles sorted by cell of a dense grid over their bounding box.
struct CellGrid {
    std::array<double, 3> origin{};
    double cell = 1;
    std::array<long, 3> dims{1, 1, 1};
    std::vector<std::uint32_t> start; // per cell, into `order`; one more at the end
    std::vector<std::uint32_t> order; // particle indices by cell

    long index(long x, long y, long z) const { return (z * dims[1] + y) * dims[0] + x; }
    long coordinate(double p, int a) const {
        return std::clamp(long(std::floor((p - origin[a]) / cell)), 0L, dims[a] - 1);
    }
};

CellGrid make_grid(const Snapshot& frame, double support) {
    const int dim = frame.dimension;
    const std::size_t n = frame.size();
    CellGrid g;
    std::array<double, 3> lo{0, 0, 0}, hi{0, 0, 0};
    for (int a = 0; a < dim; ++a) {
        lo[a] = std::numeric_limits<double>::max();
        hi[a] = std::numeric_limits<double>::lowest();
    }
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < dim; ++a) {
            lo[a] = std::min(lo[a], double(frame.position[i * dim + a]));
            hi[a] = std::max(hi[a], double(frame.position[i * dim + a]));
        }
    // Cells `support` wide, unless spray far from the fluid would make the
    // grid huge: then wider cells (the search stays exact, only slower).
    g.cell = support;
    constexpr double max_cells = 1 << 24;
    for (;;) {
        double cells = 1;
        for (int a = 0; a < dim; ++a)
            cells *= std::floor((hi[a] - lo[a]) / g.cell) + 1;
        if (cells <= max_cells)
            break;
        g.cell *= 2;
    }
    for (int a = 0; a < dim; ++a) {
        g.origin[a] = lo[a];
        g.dims[a] = long(std::floor((hi[a] - lo[a]) / g.cell)) + 1;
    }
    const std::size_t cells = std::size_t(g.dims[0] * g.dims[1] * g.dims[2]);
    std::vector<std::uint32_t> cell_of(n);
    g.start.assign(cells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
        std::array<long, 3> c{0, 0, 0};
        for (int a = 0; a < dim; ++a)
            c[a] = g.coordinate(frame.position[i * dim + a], a);
        cell_of[i] = std::uint32_t(g.index(c[0], c[1], c[2]));
        ++g.start[cell_of[i] + 1];
    }
    for (std::size_t c = 0; c < cells; ++c)
        g.start[c + 1] += g.start[c];
    g.order.resize(n);
    std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
        g.order[fill[cell_of[i]]++] = std::uint32_t(i);
    return g;
}

} // namespace

void colour_vertices(SurfaceMesh& mesh, const Snapshot& frame, const std::vector<float>& scalars,
                     double support) {
    const std::size_t nv = mesh.vertices();
    if (nv == 0)
        return;
    const int dim = frame.dimension;
    float lowest = 0;
    if (!scalars.empty())
        lowest = *std::min_element(scalars.begin(), scalars.end());
    if (frame.size() == 0) {
        std::fill(mesh.scalar.begin(), mesh.scalar.end(), lowest);
        return;
    }
    const CellGrid g = make_grid(frame, support);
    const double h2 = support * support;
    const long reach = long(std::ceil(support / g.cell));
#pragma omp parallel for schedule(static)
    for (std::size_t v = 0; v < nv; ++v) {
        std::array<double, 3> p{};
        std::array<long, 3> c{0, 0, 0}, from{0, 0, 0}, to{0, 0, 0};
        for (int a = 0; a < dim; ++a) {
            p[a] = mesh.positions[3 * v + a];
            c[a] = long(std::floor((p[a] - g.origin[a]) / g.cell));
            from[a] = std::max(c[a] - reach, 0L);
            to[a] = std::min(c[a] + reach, g.dims[a] - 1);
        }
        double sum = 0, weights = 0, nearest = std::numeric_limits<double>::max();
        float nearest_value = lowest;
        for (long z = from[2]; z <= to[2]; ++z)
            for (long y = from[1]; y <= to[1]; ++y)
                for (long x = from[0]; x <= to[0]; ++x) {
                    const long cell = g.index(x, y, z);
                    for (std::uint32_t k = g.start[cell]; k < g.start[cell + 1]; ++k) {
                        const std::uint32_t j = g.order[k];
                        double r2 = 0;
                        for (int a = 0; a < dim; ++a) {
                            const double d = frame.position[j * dim + a] - p[a];
                            r2 += d * d;
                        }
                        if (r2 < nearest) {
                            nearest = r2;
                            nearest_value = scalars[j];
                        }
                        if (r2 < h2) {
                            const double q = 1 - r2 / h2;
                            const double w = q * q * q;
                            sum += w * scalars[j];
                            weights += w;
                        }
                    }
                }
        mesh.scalar[v] = weights > 0 ? float(sum / weights) : nearest_value;
    }
}

} // namespace sph
