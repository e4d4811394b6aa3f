#include "render/sphere_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace sph {

SphereMesh make_icosphere(int subdivisions) {
    SphereMesh mesh;
    auto add = [&mesh](double x, double y, double z) {
        const double l = std::sqrt(x * x + y * y + z * z);
        mesh.vertices.push_back({float(x / l), float(y / l), float(z / l)});
        return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
    };
    // The 12 vertices of an icosahedron: cyclic permutations of (0, +-1, +-phi).
    const double t = (1 + std::sqrt(5.0)) / 2;
    for (auto [x, y] : {std::pair{-1.0, t}, {1.0, t}, {-1.0, -t}, {1.0, -t}})
        add(x, y, 0);
    for (auto [y, z] : {std::pair{-1.0, t}, {1.0, t}, {-1.0, -t}, {1.0, -t}})
        add(0, y, z);
    for (auto [z, x] : {std::pair{-1.0, t}, {1.0, t}, {-1.0, -t}, {1.0, -t}})
        add(x, 0, z);
    mesh.indices = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                    4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                    6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    // Each subdivision splits a triangle into four through its edge midpoints.
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            if (auto it = midpoints.find(key); it != midpoints.end())
                return it->second;
            const auto& p = mesh.vertices[a];
            const auto& q = mesh.vertices[b];
            const std::uint32_t m = add(p[0] + q[0], p[1] + q[1], p[2] + q[2]);
            midpoints.emplace(key, m);
            return m;
        };
        std::vector<std::uint32_t> finer;
        for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
            const std::uint32_t a = mesh.indices[i], b = mesh.indices[i + 1],
                                c = mesh.indices[i + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        mesh.indices = std::move(finer);
    }
    return mesh;
}

} // namespace sph
