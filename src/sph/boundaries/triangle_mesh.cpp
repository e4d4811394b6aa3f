#include "sph/boundaries/triangle_mesh.hpp"

#include "sph/assert.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace sph {

namespace {

using Vec3 = Vec<3>;

// The feature of a triangle a closest point lies on.
enum Feature : int { vertex_0, vertex_1, vertex_2, edge_0, edge_1, edge_2, face };

struct TrianglePoint {
    Vec3 point;
    int feature; // edge k runs from vertex k to vertex k + 1
};

// Ericson 2005, 5.1.5 (ClosestPtPointTriangle): the Voronoi regions of the
// vertices, then of the edges, else the face, tested with dot products only.
TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 ab = b - a, ac = c - a, ap = p - a;
    const Real d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0)
        return {a, vertex_0};
    const Vec3 bp = p - b;
    const Real d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3)
        return {b, vertex_1};
    const Real vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
        return {a + (d1 / (d1 - d3)) * ab, edge_0};
    const Vec3 cp = p - c;
    const Real d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6)
        return {c, vertex_2};
    const Real vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
        return {a + (d2 / (d2 - d6)) * ac, edge_2};
    const Real va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
        return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), edge_1};
    const Real scale = 1 / (va + vb + vc);
    return {a + ab * (vb * scale) + ac * (vc * scale), face};
}

Real box_distance2(const Box<3>& box, const Vec3& x) {
    const Vec3 gap = glm::max(glm::max(box.min - x, x - box.max), Vec3(0));
    return glm::dot(gap, gap);
}

void grow(Box<3>& box, const Vec3& x) {
    box.min = glm::min(box.min, x);
    box.max = glm::max(box.max, x);
}

Box<3> empty_box() {
    const Real inf = std::numeric_limits<Real>::infinity();
    return {Vec3(inf), Vec3(-inf)};
}

// An undirected edge as one key, the smaller index first.
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
    return (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

} // namespace

std::string mesh_solid_problem(const std::vector<Vec3>& vertices,
                               const std::vector<Triangle>& triangles) {
    if (triangles.empty())
        return "it has no triangles (faces)";
    Box<3> bounds = empty_box();
    for (std::size_t t = 0; t < triangles.size(); ++t)
        for (const std::uint32_t v : triangles[t]) {
            if (v >= vertices.size())
                return fmt::format("face {} names vertex {}, but there are {} vertices", t + 1,
                                   std::uint64_t(v) + 1, vertices.size());
            for (int a = 0; a < 3; ++a)
                if (!std::isfinite(vertices[v][a]))
                    return fmt::format("vertex {} has a coordinate that is not a finite number",
                                       std::uint64_t(v) + 1);
            grow(bounds, vertices[v]);
        }
    // Areas and volumes relative to the mesh's size: rounding in the file's
    // digits is not mistaken for a degenerate face.
    const Real size = glm::length(bounds.max - bounds.min);
    if (!(size > 0) || !std::isfinite(size))
        return "its vertices are all at one point";
    // Directed edges: in a closed, consistently oriented mesh each edge is
    // walked once each way (by its two triangles).
    std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>> uses; // forward, backward
    uses.reserve(3 * triangles.size());
    Real volume = 0;
    for (std::size_t t = 0; t < triangles.size(); ++t) {
        const Triangle& tri = triangles[t];
        const Vec3 &a = vertices[tri[0]], &b = vertices[tri[1]], &c = vertices[tri[2]];
        const Real area = 0.5 * glm::length(glm::cross(b - a, c - a));
        if (!(area > 1e-12 * size * size))
            return fmt::format("face {} (vertices {}, {}, {}) is degenerate: it has no area", t + 1,
                               std::uint64_t(tri[0]) + 1, std::uint64_t(tri[1]) + 1,
                               std::uint64_t(tri[2]) + 1);
        volume += glm::dot(a, glm::cross(b, c)) / 6;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t from = tri[k], to = tri[(k + 1) % 3];
            ++uses[edge_key(from, to)][from < to ? 0 : 1];
        }
    }
    // Counts, and the first edge of each fault in vertex order (the same
    // message every run).
    std::array<std::size_t, 3> faults{0, 0, 0}; // open, shared by more than two, flipped
    std::array<std::uint64_t, 3> example{0, 0, 0};
    for (const auto& [key, count] : uses) {
        const std::uint32_t total = count[0] + count[1];
        const int fault = total == 1 ? 0 : total > 2 ? 1 : count[0] != 1 ? 2 : -1;
        if (fault >= 0 && (faults[fault]++ == 0 || key < example[fault]))
            example[fault] = key;
    }
    auto edge = [&](int fault) {
        return fmt::format("e.g. the edge from vertex {} to {}", (example[fault] >> 32) + 1,
                           (example[fault] & 0xffffffffu) + 1);
    };
    if (faults[0] > 0)
        return fmt::format("it is not closed: {} edges belong to one face only ({}); a solid "
                           "needs a watertight surface",
                           faults[0], edge(0));
    if (faults[1] > 0)
        return fmt::format("it is not a manifold: {} edges are shared by more than two faces ({})",
                           faults[1], edge(1));
    if (faults[2] > 0)
        return fmt::format("its faces are not consistently oriented: {} edges are walked the same "
                           "way by both their faces ({})",
                           faults[2], edge(2));
    if (!(std::abs(volume) > 1e-9 * size * size * size))
        return "it encloses no volume";
    return {};
}

TriangleMesh::TriangleMesh(std::vector<Vec3> vertices, std::vector<Triangle> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
    SPHCLIP_ASSERT(mesh_solid_problem(vertices_, triangles_).empty());
    for (const Triangle& t : triangles_)
        volume_ += glm::dot(vertices_[t[0]], glm::cross(vertices_[t[1]], vertices_[t[2]])) / 6;
    // Outward normals: counter-clockwise seen from outside encloses a
    // positive volume.
    if (volume_ < 0) {
        for (Triangle& t : triangles_)
            std::swap(t[1], t[2]);
        volume_ = -volume_;
    }
    const std::size_t n = triangles_.size();
    face_normals_.resize(n);
    vertex_normals_.assign(vertices_.size(), Vec3(0));
    edge_normals_.resize(n);
    bounds_ = empty_box();
    std::unordered_map<std::uint64_t, std::uint32_t> forward; // directed edge -> its triangle
    forward.reserve(3 * n);
    for (std::uint32_t t = 0; t < n; ++t) {
        const Triangle& tri = triangles_[t];
        const Vec3 cross = glm::cross(vertices_[tri[1]] - vertices_[tri[0]],
                                      vertices_[tri[2]] - vertices_[tri[0]]);
        area_ += 0.5 * glm::length(cross);
        face_normals_[t] = glm::normalize(cross);
        for (int k = 0; k < 3; ++k) {
            grow(bounds_, vertices_[tri[k]]);
            // Baerentzen & Aanaes: each face's normal weighted by its angle at the vertex.
            const Vec3 u = glm::normalize(vertices_[tri[(k + 1) % 3]] - vertices_[tri[k]]);
            const Vec3 v = glm::normalize(vertices_[tri[(k + 2) % 3]] - vertices_[tri[k]]);
            const Real angle = std::acos(std::clamp(glm::dot(u, v), Real(-1), Real(1)));
            vertex_normals_[tri[k]] += angle * face_normals_[t];
            forward[(std::uint64_t(tri[k]) << 32) | tri[(k + 1) % 3]] = t;
        }
    }
    // An edge's pseudo-normal: the sum of its two faces' normals (each face
    // meets it at an angle of pi).
    for (std::uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 3; ++k) {
            const Triangle& tri = triangles_[t];
            const std::uint32_t other =
                forward.at((std::uint64_t(tri[(k + 1) % 3]) << 32) | tri[k]);
            edge_normals_[t][k] = face_normals_[t] + face_normals_[other];
        }
    order_.resize(n);
    std::iota(order_.begin(), order_.end(), 0u);
    nodes_.reserve(2 * n / 4 + 1);
    build(0, std::uint32_t(n));
}

std::uint32_t TriangleMesh::build(std::uint32_t begin, std::uint32_t end) {
    constexpr std::uint32_t leaf_size = 4;
    const auto index = std::uint32_t(nodes_.size());
    nodes_.emplace_back();
    Box<3> box = empty_box(), centres = empty_box();
    auto centre = [&](std::uint32_t t) {
        const Triangle& tri = triangles_[t];
        return (vertices_[tri[0]] + vertices_[tri[1]] + vertices_[tri[2]]) / Real(3);
    };
    for (std::uint32_t i = begin; i < end; ++i) {
        for (const std::uint32_t v : triangles_[order_[i]])
            grow(box, vertices_[v]);
        grow(centres, centre(order_[i]));
    }
    nodes_[index].box = box;
    if (end - begin <= leaf_size) {
        nodes_[index].first = begin;
        nodes_[index].count = end - begin;
        return index;
    }
    const Vec3 extent = centres.max - centres.min;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                     : extent.y >= extent.z                       ? 1
                                                                  : 2;
    const std::uint32_t middle = begin + (end - begin) / 2;
    std::nth_element(
        order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
        [&](std::uint32_t s, std::uint32_t t) { return centre(s)[axis] < centre(t)[axis]; });
    build(begin, middle); // the first child is the next node
    const std::uint32_t right = build(middle, end);
    nodes_[index].right = right;
    return index;
}

TriangleMesh::Nearest TriangleMesh::nearest(const Vec3& x) const {
    Real best = std::numeric_limits<Real>::infinity(); // squared distance
    Vec3 point(0), pseudo_normal(0);
    // Depth is at most log2(triangles) + 1 with median splits.
    std::array<std::uint32_t, 64> stack;
    std::size_t top = 0;
    stack[top++] = 0;
    while (top > 0) {
        const Node& node = nodes_[stack[--top]];
        if (!(box_distance2(node.box, x) < best))
            continue;
        if (node.count > 0) {
            for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
                const std::uint32_t t = order_[i];
                const Triangle& tri = triangles_[t];
                const TrianglePoint c =
                    closest_on_triangle(x, vertices_[tri[0]], vertices_[tri[1]], vertices_[tri[2]]);
                const Real d2 = squared_length<3>(x - c.point);
                if (!(d2 < best))
                    continue;
                best = d2;
                point = c.point;
                pseudo_normal = c.feature == face     ? face_normals_[t]
                                : c.feature >= edge_0 ? edge_normals_[t][c.feature - edge_0]
                                                      : vertex_normals_[tri[c.feature]];
            }
            continue;
        }
        // The nearer child is searched first: its result prunes the other.
        const auto self = std::uint32_t(&node - nodes_.data());
        std::uint32_t first = self + 1, second = node.right;
        Real near = box_distance2(nodes_[first].box, x), far = box_distance2(nodes_[second].box, x);
        if (far < near) {
            std::swap(first, second);
            std::swap(near, far);
        }
        SPHCLIP_ASSERT(top + 2 <= stack.size());
        if (far < best)
            stack[top++] = second;
        if (near < best)
            stack[top++] = first;
    }
    Nearest out;
    out.point = point;
    out.normal = glm::normalize(pseudo_normal);
    const Real distance = std::sqrt(best);
    out.distance = glm::dot(x - point, pseudo_normal) < 0 ? -distance : distance;
    return out;
}

} // namespace sph
