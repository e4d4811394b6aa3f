#pragma once
// A closed triangle mesh as a solid (3D obstacles read from OBJ files): the
// signed distance of a point to its surface, negative inside, and the
// closest point with its normal.
//
// - Closest point on a triangle: Ericson, "Real-Time Collision Detection"
//   (2005), 5.1.5, by the triangle's Voronoi regions, which also tells the
//   feature (vertex, edge or face) the point lies on.
// - Inside or outside: the sign of (x - closest) . n, n the angle-weighted
//   pseudo-normal of that feature (Baerentzen & Aanaes 2005, "Signed distance
//   computation using the angle weighted pseudonormal"): the face's normal,
//   the sum of an edge's two face normals, or a vertex's face normals
//   weighted by their angles at it. Exact for a closed, consistently
//   oriented mesh, where a ray-parity count would need care at edges.
// - The nearest triangle: a bounding volume hierarchy (Ericson ch. 6,
//   median split of centroids on the longest axis), searched nearest child
//   first and pruned by the best distance found so far.

#include "sph/vec.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sph {

using Triangle = std::array<std::uint32_t, 3>; // vertex indices

// Why `triangles` over `vertices` is not a solid, or empty when it is one:
// no triangle, an index out of range, a non-finite coordinate, a triangle
// without area, an edge not shared by exactly two triangles (an open or
// non-manifold mesh), two triangles that disagree on the orientation of
// their shared edge, or no enclosed volume.
std::string mesh_solid_problem(const std::vector<Vec<3>>& vertices,
                               const std::vector<Triangle>& triangles);

class TriangleMesh {
  public:
    // The mesh must be a solid (mesh_solid_problem empty). Triangles wound
    // clockwise seen from outside (a negative enclosed volume) are turned.
    TriangleMesh(std::vector<Vec<3>> vertices, std::vector<Triangle> triangles);

    struct Nearest {
        Vec<3> point{0};   // m, the closest point on the surface
        Vec<3> normal{0};  // unit outward pseudo-normal of the feature it lies on
        Real distance = 0; // m, negative inside
    };
    Nearest nearest(const Vec<3>& x) const;
    Real signed_distance(const Vec<3>& x) const { return nearest(x).distance; }

    const std::vector<Vec<3>>& vertices() const { return vertices_; }
    const std::vector<Triangle>& triangles() const { return triangles_; }
    // Unit outward normal of each triangle.
    const std::vector<Vec<3>>& face_normals() const { return face_normals_; }
    const Box<3>& bounds() const { return bounds_; }
    Real area() const { return area_; }     // m^2
    Real volume() const { return volume_; } // m^3, enclosed

  private:
    struct Node {
        Box<3> box;
        std::uint32_t first = 0, count = 0; // a leaf's triangles in order_
        std::uint32_t right = 0;            // an inner node's second child; the first follows it
    };
    std::uint32_t build(std::uint32_t begin, std::uint32_t end);

    std::vector<Vec<3>> vertices_;
    std::vector<Triangle> triangles_;
    std::vector<Vec<3>> face_normals_;
    std::vector<Vec<3>> vertex_normals_;              // angle-weighted sums
    std::vector<std::array<Vec<3>, 3>> edge_normals_; // edge k: vertex k to k + 1
    std::vector<std::uint32_t> order_;                // triangles, grouped by leaf
    std::vector<Node> nodes_;                         // nodes_[0] is the root
    Box<3> bounds_;
    Real area_ = 0, volume_ = 0;
};

} // namespace sph
