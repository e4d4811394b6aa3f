#include "io/obj_mesh.hpp"

#include "io/input_error.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <sstream>
#include <tiny_obj_loader.h>

namespace sph {

std::shared_ptr<const TriangleMesh> read_obj_mesh(const std::filesystem::path& path, Real scale,
                                                  const Vec<3>& offset,
                                                  const std::string& scene_file,
                                                  const std::string& field) {
    auto fail = [&](const std::string& why) {
        throw InputError(scene_file, field, fmt::format("\"{}\": {}", path.string(), why));
    };
    std::error_code ec;
    std::ifstream in(path, std::ios::binary);
    if (!in || std::filesystem::is_directory(path, ec))
        fail("cannot read the mesh file (missing or unreadable)");
    std::stringstream text;
    text << in.rdbuf();

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // From memory with no material text: an `mtllib` line opens nothing.
    if (!reader.ParseFromString(text.str(), "", config))
        fail(fmt::format("not a readable OBJ file ({})", reader.Error()));

    const std::vector<tinyobj::real_t>& coordinates = reader.GetAttrib().vertices;
    std::vector<Vec<3>> vertices(coordinates.size() / 3);
    // Exactly repeated positions are one vertex: an exporter that writes a
    // corner once per face would otherwise leave every edge open.
    std::map<std::array<Real, 3>, std::uint32_t> first_at;
    std::vector<std::uint32_t> joined(vertices.size());
    for (std::size_t v = 0; v < vertices.size(); ++v) {
        const std::array<Real, 3> p{Real(coordinates[3 * v]), Real(coordinates[3 * v + 1]),
                                    Real(coordinates[3 * v + 2])};
        joined[v] = first_at.emplace(p, std::uint32_t(v)).first->second;
        for (int a = 0; a < 3; ++a)
            vertices[v][a] = scale * p[a] + offset[a];
    }
    std::vector<Triangle> triangles;
    for (const tinyobj::shape_t& shape : reader.GetShapes()) {
        const auto& indices = shape.mesh.indices;
        std::size_t next = 0;
        for (const unsigned char corners : shape.mesh.num_face_vertices) {
            if (corners != 3 || next + 3 > indices.size())
                fail("a face could not be split into triangles");
            Triangle t;
            for (int k = 0; k < 3; ++k) {
                const int v = indices[next + k].vertex_index;
                if (v < 0 || std::size_t(v) >= vertices.size())
                    fail(fmt::format("face {} names a vertex that the file does not have (it "
                                     "has {})",
                                     triangles.size() + 1, vertices.size()));
                t[k] = joined[std::size_t(v)];
            }
            next += 3;
            triangles.push_back(t);
        }
    }
    if (triangles.empty()) {
        // The loader's warnings say what it skipped, e.g. faces of two vertices.
        std::string warning = reader.Warning();
        std::replace(warning.begin(), warning.end(), '\n', ' ');
        fail(warning.find_first_not_of(" .") == std::string::npos
                 ? std::string("not a mesh: no triangles (no `f` lines of 3 or more vertices)")
                 : fmt::format("not a mesh: no triangles (the OBJ reader says: {})",
                               warning.substr(0, 200)));
    }
    if (const std::string problem = mesh_solid_problem(vertices, triangles); !problem.empty())
        fail("not a closed solid: " + problem);
    return std::make_shared<const TriangleMesh>(std::move(vertices), std::move(triangles));
}

} // namespace sph
