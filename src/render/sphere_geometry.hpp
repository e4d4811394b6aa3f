#pragma once
// The seed's sphere mesh: an icosphere (an icosahedron subdivided), shared by
// every particle through instancing.

#include <array>
#include <cstdint>
#include <vector>

namespace sph {

struct SphereMesh {
    std::vector<std::array<float, 3>> vertices; // on the unit sphere, also the normals
    std::vector<std::uint32_t> indices;         // triangles
};

// subdivisions 0: 20 triangles, 1: 80, 2: 320.
SphereMesh make_icosphere(int subdivisions);

} // namespace sph
