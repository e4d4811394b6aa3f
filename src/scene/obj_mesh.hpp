#pragma once
// Closed triangle meshes from Wavefront OBJ files (3D mesh obstacles), read
// with tinyobjloader (Debian libtinyobjloader-dev): `v` vertices and `f`
// faces, polygons split into triangles; normals, texture coordinates,
// groups and materials are ignored, and `mtllib` is not followed (the text
// is parsed from memory), so reading a mesh opens no other file.

#include "sph/boundaries/triangle_mesh.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// The mesh in `path`, each vertex moved to scale * v + offset, checked to
// be a solid (closed, manifold, consistently oriented, no degenerate face:
// mesh_solid_problem). Vertices repeated at exactly the same position are
// joined first, as some exporters repeat them. Throws InputError(scene_file,
// field, why) naming the OBJ file. Only a regular file within
// mesh_file_limit is read (output/files.hpp); a vertex lies within 1e12 m of
// the origin once placed. Faces of more than three corners are split by
// split_polygon.
std::shared_ptr<const TriangleMesh> read_obj_mesh(const std::filesystem::path& path, Real scale,
                                                  const Vec<3>& offset,
                                                  const std::string& scene_file,
                                                  const std::string& field);

// The same from the file's text; `path` names it in errors.
std::shared_ptr<const TriangleMesh>
parse_obj_mesh(std::string_view text, const std::filesystem::path& path, Real scale,
               const Vec<3>& offset, const std::string& scene_file, const std::string& field);

// The triangles (corner numbers, in the polygon's own winding) that split
// the polygon `corners` (3D, about planar), by ear clipping in the plane
// nearest to it: n - 2 triangles for n corners. A polygon that crosses
// itself is split too, with triangles that overlap: the solid check
// refuses what they make. Near linear in the corners for the polygons of
// real meshes (only reflex corners are tested, found through a grid); none
// (an empty list) for a polygon on which that would take more than about a
// second.
std::vector<Triangle> split_polygon(const std::vector<Vec<3>>& corners);

} // namespace sph
