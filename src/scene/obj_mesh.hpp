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

namespace sph {

// The mesh in `path`, each vertex moved to scale * v + offset, checked to
// be a solid (closed, manifold, consistently oriented, no degenerate face:
// mesh_solid_problem). Vertices repeated at exactly the same position are
// joined first, as some exporters repeat them. Throws InputError(scene_file,
// field, why) naming the OBJ file. Only a regular file within
// mesh_file_limit is read (output/files.hpp); a face has at most 256 corners and
// a vertex lies within 1e12 m of the origin once placed.
std::shared_ptr<const TriangleMesh> read_obj_mesh(const std::filesystem::path& path, Real scale,
                                                  const Vec<3>& offset,
                                                  const std::string& scene_file,
                                                  const std::string& field);

// The same from the file's text; `path` names it in errors.
std::shared_ptr<const TriangleMesh>
parse_obj_mesh(std::string_view text, const std::filesystem::path& path, Real scale,
               const Vec<3>& offset, const std::string& scene_file, const std::string& field);

} // namespace sph
