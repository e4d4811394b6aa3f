// The 2D surface (reconstruct.hpp): the fluid's region as the half-full level
// of a kernel sum on a grid, traced by marching squares (Lorensen and Cline's
// marching cubes in two dimensions), each cell's inside part filled.
#include "render/surface/reconstruct.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace sph {

namespace {

// Node values of a grid: the kernel sum, and the colour sum weighted alike.
struct NodeGrid {
    double x0 = 0, y0 = 0, dx = 1;
    long nx = 0, ny = 0;
    std::vector<float> weight, colour; // per node, x fastest

    std::size_t node(long i, long j) const { return std::size_t(j * nx + i); }
};

// One pass of a 3x3 binomial blur (1 2 1 / 4 in each direction) over both sums.
void blur(NodeGrid& g) {
    std::vector<float> w(g.weight.size()), c(g.colour.size());
    for (int axis = 0; axis < 2; ++axis) {
        for (long j = 0; j < g.ny; ++j)
            for (long i = 0; i < g.nx; ++i) {
                float sw = 2 * g.weight[g.node(i, j)], sc = 2 * g.colour[g.node(i, j)];
                for (int side : {-1, 1}) {
                    const long a = axis == 0 ? std::clamp(i + side, 0L, g.nx - 1) : i;
                    const long b = axis == 1 ? std::clamp(j + side, 0L, g.ny - 1) : j;
                    sw += g.weight[g.node(a, b)];
                    sc += g.colour[g.node(a, b)];
                }
                w[g.node(i, j)] = 0.25f * sw;
                c[g.node(i, j)] = 0.25f * sc;
            }
        g.weight.swap(w);
        g.colour.swap(c);
    }
}

// The particles' kernel sums on a grid of nodes, a border of empty nodes
// all round; weight and weight x scalar per node.
NodeGrid splat(const Snapshot& frame, const std::vector<float>& scalars, double spacing,
               const SurfaceSettings& settings) {
    const std::size_t n = frame.size();
    // Kernel support R: twice the radius, so neighbours overlap and the sum
    // is smooth between them.
    const double support = 2 * settings.radius * spacing;
    NodeGrid g;
    g.dx = settings.voxel * spacing;
    double lo[2] = {std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
    double hi[2] = {std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < 2; ++a) {
            lo[a] = std::min(lo[a], double(frame.position[2 * i + a]));
            hi[a] = std::max(hi[a], double(frame.position[2 * i + a]));
        }
    // A border of empty nodes all round, so the outline closes; the blur's
    // reach added.
    const double border = support + (settings.smoothing + 2) * g.dx;
    g.x0 = lo[0] - border;
    g.y0 = lo[1] - border;
    g.nx = long(std::ceil((hi[0] - lo[0] + 2 * border) / g.dx)) + 1;
    g.ny = long(std::ceil((hi[1] - lo[1] + 2 * border) / g.dx)) + 1;
    g.weight.assign(std::size_t(g.nx * g.ny), 0.f);
    g.colour.assign(g.weight.size(), 0.f);
    const double r2 = support * support;
    const long reach = long(std::ceil(support / g.dx));
    for (std::size_t p = 0; p < n; ++p) {
        const double px = frame.position[2 * p], py = frame.position[2 * p + 1];
        const long ci = long(std::floor((px - g.x0) / g.dx)),
                   cj = long(std::floor((py - g.y0) / g.dx));
        for (long j = std::max(cj - reach, 0L); j <= std::min(cj + reach + 1, g.ny - 1); ++j)
            for (long i = std::max(ci - reach, 0L); i <= std::min(ci + reach + 1, g.nx - 1); ++i) {
                const double dx = g.x0 + double(i) * g.dx - px, dy = g.y0 + double(j) * g.dx - py;
                const double d2 = dx * dx + dy * dy;
                if (d2 >= r2)
                    continue;
                const double q = 1 - d2 / r2;
                const float w = float(q * q * q);
                g.weight[g.node(i, j)] += w;
                g.colour[g.node(i, j)] += w * scalars[p];
            }
    }
    return g;
}

// Marching squares over the grid: the cells' inside parts as triangles, and
// the outline where the sum crosses iso, into mesh.
void march(const NodeGrid& g, float iso, SurfaceMesh& mesh) {
    // Vertices made once and shared by the cells that meet there: at nodes
    // inside, and where an edge crosses the outline (per node, the edge to
    // +x and the edge to +y).
    const std::size_t nodes = g.weight.size();
    std::vector<std::int64_t> at_node(nodes, -1), on_x_edge(nodes, -1), on_y_edge(nodes, -1);
    auto add_vertex = [&](double x, double y, float colour) {
        mesh.positions.insert(mesh.positions.end(), {float(x), float(y), 0.f});
        mesh.normals.insert(mesh.normals.end(), {0.f, 0.f, 1.f});
        mesh.scalar.push_back(colour);
        return std::int64_t(mesh.scalar.size() - 1);
    };
    auto node_vertex = [&](long i, long j) {
        std::int64_t& v = at_node[g.node(i, j)];
        if (v < 0)
            v = add_vertex(g.x0 + double(i) * g.dx, g.y0 + double(j) * g.dx,
                           g.colour[g.node(i, j)] / g.weight[g.node(i, j)]);
        return v;
    };
    auto edge_vertex = [&](long i, long j, int axis) {
        std::int64_t& v = (axis == 0 ? on_x_edge : on_y_edge)[g.node(i, j)];
        if (v >= 0)
            return v;
        const std::size_t a = g.node(i, j), b = axis == 0 ? g.node(i + 1, j) : g.node(i, j + 1);
        const double t =
            std::clamp(double(iso - g.weight[a]) / double(g.weight[b] - g.weight[a]), 0.0, 1.0);
        const double w = (1 - t) * g.weight[a] + t * g.weight[b];
        const double c = (1 - t) * g.colour[a] + t * g.colour[b];
        const double x = g.x0 + (double(i) + (axis == 0 ? t : 0)) * g.dx;
        const double y = g.y0 + (double(j) + (axis == 1 ? t : 0)) * g.dx;
        v = add_vertex(x, y, float(w > 0 ? c / w : 0));
        return v;
    };
    // Corners counter-clockwise from (i, j); edge k joins corner k to k + 1.
    constexpr long corner_i[4] = {0, 1, 1, 0}, corner_j[4] = {0, 0, 1, 1};
    for (long j = 0; j + 1 < g.ny; ++j)
        for (long i = 0; i + 1 < g.nx; ++i) {
            std::array<bool, 4> inside{};
            int count = 0;
            for (int k = 0; k < 4; ++k) {
                inside[k] = g.weight[g.node(i + corner_i[k], j + corner_j[k])] >= iso;
                count += inside[k];
            }
            if (count == 0)
                continue;
            // The cell's inside part, walking its border: inside corners and
            // crossings in order. A corner cut off a square keeps it convex,
            // so a fan from the first vertex fills it; the saddle cases join
            // their two inside corners (the fluid read as connected).
            std::array<std::int64_t, 8> polygon{};
            std::array<bool, 8> crossing{};
            int size = 0;
            for (int k = 0; k < 4; ++k) {
                const int next = (k + 1) % 4;
                if (inside[k]) {
                    crossing[size] = false;
                    polygon[size++] = node_vertex(i + corner_i[k], j + corner_j[k]);
                }
                if (inside[k] != inside[next]) {
                    // Edges 0 and 2 run along x, 1 and 3 along y; each from its
                    // lower node.
                    const long ei = i + (k == 1 ? 1 : 0), ej = j + (k == 2 ? 1 : 0);
                    crossing[size] = true;
                    polygon[size++] = edge_vertex(ei, ej, k % 2 == 0 ? 0 : 1);
                }
            }
            for (int k = 1; k + 1 < size; ++k)
                mesh.triangles.insert(mesh.triangles.end(),
                                      {std::uint32_t(polygon[0]), std::uint32_t(polygon[k]),
                                       std::uint32_t(polygon[k + 1])});
            // The outline: two crossings in a row around the walk cut off an
            // outside corner; they are one segment.
            for (int k = 0; k < size; ++k) {
                const int next = (k + 1) % size;
                if (crossing[k] && crossing[next])
                    mesh.outline.insert(mesh.outline.end(),
                                        {std::uint32_t(polygon[k]), std::uint32_t(polygon[next])});
            }
        }
}

} // namespace

SurfaceMesh reconstruct_region_2d(const Snapshot& frame, const std::vector<float>& scalars,
                                  double spacing, const SurfaceSettings& settings) {
    SurfaceMesh mesh;
    mesh.dimension = 2;
    if (frame.size() == 0)
        return mesh;
    NodeGrid g = splat(frame, scalars, spacing, settings);
    for (int pass = 0; pass < settings.smoothing; ++pass)
        blur(g);
    // The sum deep inside a lattice of spacing s: the kernel's integral,
    // pi R^2 / 4, over the area s^2 each particle stands for. The outline is
    // where half of that is reached: half a spacing beyond the outermost
    // particles, where the drawn discs' edge would be.
    const double support = 2 * settings.radius * spacing, r2 = support * support;
    const float iso = float(0.5 * (std::numbers::pi * r2 / 4) / (spacing * spacing));
    march(g, iso, mesh);
    return mesh;
}

} // namespace sph
