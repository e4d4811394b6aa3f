#include "scene/obj_mesh.hpp"

#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <string_view>
#include <tiny_obj_loader.h>
#include <vector>

namespace sph {

namespace {

// The most corners one `f` line may have. tinyobjloader splits a polygon by
// ear clipping, quadratic in its corners: a 200,000-corner face took minutes.
// No exporter writes solids that way; triangles and quads are the rule.
constexpr std::size_t max_face_corners = 256;
// Past this distance from the origin a vertex is a mistake, not a solid:
// the solid checks' cross products would overflow long before.
constexpr Real max_vertex_distance = 1e12; // m

// Where each `v` line is and what it says, to name a bad vertex.
struct VertexLine {
    std::size_t line;
    std::vector<std::string> words;
};

// Checks what tinyobjloader would take too long on or read wrongly, naming
// the line: a face with too many corners, a vertex coordinate that is not a
// finite number. Returns the `v` lines, for check_vertices.
std::vector<VertexLine> scan_obj_lines(std::string_view text,
                                       const std::function<void(const std::string&)>& fail) {
    std::vector<VertexLine> vertex_lines;
    std::size_t line_number = 0;
    for (std::size_t begin = 0; begin < text.size();) {
        std::size_t end = text.find('\n', begin);
        if (end == std::string_view::npos)
            end = text.size();
        std::string_view line = text.substr(begin, end - begin);
        begin = end + 1;
        ++line_number;
        const std::size_t first = line.find_first_not_of(" \t");
        if (first == std::string_view::npos || line.size() < first + 2)
            continue;
        line.remove_prefix(first);
        const bool face = line[0] == 'f' && (line[1] == ' ' || line[1] == '\t');
        const bool vertex = line[0] == 'v' && (line[1] == ' ' || line[1] == '\t');
        if (!face && !vertex)
            continue;
        std::vector<std::string> words;
        for (std::size_t at = 1; at < line.size();) {
            const std::size_t w = line.find_first_not_of(" \t\r", at);
            if (w == std::string_view::npos)
                break;
            const std::size_t w_end = std::min(line.find_first_of(" \t\r", w), line.size());
            if (vertex && words.size() < 3)
                words.emplace_back(line.substr(w, w_end - w));
            else if (face)
                words.emplace_back();
            at = w_end;
            if (face && words.size() > max_face_corners)
                fail(fmt::format("line {}: a face of more than {} corners; split it into "
                                 "triangles (sphclip reads faces of at most {} corners)",
                                 line_number, max_face_corners, max_face_corners));
        }
        if (vertex) {
            // tinyobjloader reads "nan" or "x" as 0: check the text itself.
            for (const std::string& word : words) {
                char* stop = nullptr;
                const double x = std::strtod(word.c_str(), &stop);
                if (stop == word.c_str() || *stop != '\0' || !std::isfinite(x))
                    fail(fmt::format("line {}: vertex coordinate \"{}\" is not a finite number",
                                     line_number, word.substr(0, 40)));
            }
            vertex_lines.push_back({line_number, std::move(words)});
        }
    }
    return vertex_lines;
}

// Refuses a vertex, as tinyobjloader read it, that is not a finite number
// or lies absurdly far once placed, naming its line and its text ("0e3000"
// is read as infinity times zero).
void check_vertices(const std::vector<tinyobj::real_t>& coordinates, Real scale,
                    const Vec<3>& offset, const std::vector<VertexLine>& lines,
                    const std::function<void(const std::string&)>& fail) {
    const std::size_t count = coordinates.size() / 3;
    for (std::size_t v = 0; v < count; ++v)
        for (int a = 0; a < 3; ++a) {
            const double x = double(coordinates[3 * v + std::size_t(a)]);
            const double placed = scale * x + offset[a];
            if (std::isfinite(placed) && std::abs(placed) <= max_vertex_distance)
                continue;
            const bool located = lines.size() == count && std::size_t(a) < lines[v].words.size();
            const std::string where =
                located ? fmt::format("line {}: vertex coordinate \"{}\"", lines[v].line,
                                      lines[v].words[std::size_t(a)].substr(0, 40))
                        : fmt::format("vertex {} coordinate {}", v + 1, "xyz"[a]);
            fail(fmt::format("{} is {}", where,
                             std::isfinite(placed)
                                 ? fmt::format("{:g} m from the origin once scaled; at most {:g} m",
                                               std::abs(placed), max_vertex_distance)
                                 : std::string("not a finite number")));
        }
}

} // namespace

std::shared_ptr<const TriangleMesh> read_obj_mesh(const std::filesystem::path& path, Real scale,
                                                  const Vec<3>& offset,
                                                  const std::string& scene_file,
                                                  const std::string& field) {
    std::string text;
    try {
        text = read_input_file(path, mesh_file_limit);
    } catch (const FileReadError& e) {
        throw InputError(
            scene_file, field,
            fmt::format("\"{}\": cannot read the mesh file: {}", path.string(), e.reason));
    }
    return parse_obj_mesh(text, path, scale, offset, scene_file, field);
}

std::shared_ptr<const TriangleMesh>
parse_obj_mesh(std::string_view text, const std::filesystem::path& path, Real scale,
               const Vec<3>& offset, const std::string& scene_file, const std::string& field) {
    auto fail = [&](const std::string& why) {
        throw InputError(scene_file, field, fmt::format("\"{}\": {}", path.string(), why));
    };
    const std::vector<VertexLine> vertex_lines = scan_obj_lines(text, fail);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // From memory with no material text: an `mtllib` line opens nothing.
    if (!reader.ParseFromString(std::string(text), "", config))
        fail(fmt::format("not a readable OBJ file ({})", reader.Error()));

    const std::vector<tinyobj::real_t>& coordinates = reader.GetAttrib().vertices;
    check_vertices(coordinates, scale, offset, vertex_lines, fail);
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
