#include "scene/obj_mesh.hpp"

#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <functional>
#include <map>
#include <queue>
#include <string_view>
#include <tiny_obj_loader.h>
#include <tuple>
#include <vector>

namespace sph {

namespace {

// Past this distance from the origin a vertex is a mistake, not a solid:
// the solid checks' cross products would overflow long before.
constexpr Real max_vertex_distance = 1e12; // m

// Where each `v` line is and what it says, to name a bad vertex.
struct VertexLine {
    std::size_t line;
    std::vector<std::string> words;
};

// An `f` line of more than three corners, split by split_polygon rather
// than by tinyobjloader (whose ear clipping tests every corner against every
// ear: minutes for 200,000 corners, and at most 255 corners kept).
struct PolygonLine {
    std::size_t line;
    std::vector<std::int64_t> corners; // 0-based vertex numbers, as written
};

struct ObjLines {
    std::vector<VertexLine> vertices;
    std::vector<PolygonLine> polygons;
    // The text for tinyobjloader: each polygon's `f` made a comment (`#`),
    // so that it reads the vertices and the triangles only.
    std::string triangles_only;
};

// The vertex a face corner ("7", "7/2", "7//3", "-1/2/3") names, 0-based:
// a negative number counts back from the last vertex before the face.
std::int64_t corner_vertex(std::string_view word, std::size_t vertices_before,
                           std::size_t line_number,
                           const std::function<void(const std::string&)>& fail) {
    const std::string_view number = word.substr(0, word.find('/'));
    std::int64_t index = 0;
    const auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), index);
    if (error != std::errc() || end != number.data() + number.size() || index == 0)
        fail(fmt::format("line {}: face corner \"{}\" does not name a vertex (1 is the first, "
                         "-1 the last before the face)",
                         line_number, word.substr(0, 40)));
    return index > 0 ? index - 1 : std::int64_t(vertices_before) + index;
}

// Checks what tinyobjloader would read wrongly, naming the line: a vertex
// coordinate that is not a finite number. Returns the `v` lines, for
// check_vertices, and the polygons.
ObjLines scan_obj_lines(std::string_view text,
                        const std::function<void(const std::string&)>& fail) {
    ObjLines lines;
    lines.triangles_only = std::string(text);
    std::size_t line_number = 0;
    for (std::size_t begin = 0; begin < text.size();) {
        // Lines end as tinyobjloader ends them: at "\n", "\r\n" or a lone
        // "\r" (a polygon on a line that only it saw as one would reach its
        // quadratic splitting).
        std::size_t end = text.find_first_of("\r\n", begin);
        if (end == std::string_view::npos)
            end = text.size();
        std::string_view line = text.substr(begin, end - begin);
        // tinyobjloader reads a line as a C string: it ends at a NUL.
        line = line.substr(0, line.find('\0'));
        const std::size_t line_begin = begin;
        begin = end + (text.substr(end, 2) == "\r\n" ? 2 : 1);
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
        std::vector<std::string_view> corners;
        for (std::size_t at = 1; at < line.size();) {
            const std::size_t w = line.find_first_not_of(" \t\r", at);
            if (w == std::string_view::npos)
                break;
            const std::size_t w_end = std::min(line.find_first_of(" \t\r", w), line.size());
            if (vertex && words.size() < 3)
                words.emplace_back(line.substr(w, w_end - w));
            else if (face)
                corners.push_back(line.substr(w, w_end - w));
            at = w_end;
        }
        if (face && corners.size() > 3) {
            PolygonLine polygon{line_number, {}};
            polygon.corners.reserve(corners.size());
            for (const std::string_view corner : corners)
                polygon.corners.push_back(
                    corner_vertex(corner, lines.vertices.size(), line_number, fail));
            lines.polygons.push_back(std::move(polygon));
            lines.triangles_only[line_begin + first] = '#';
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
            lines.vertices.push_back({line_number, std::move(words)});
        }
    }
    return lines;
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

namespace {

// Ear clipping of one polygon (split_polygon below): the polygon projected
// on a plane, its corners as a doubly linked ring, the corners that may
// block an ear in a uniform grid, and the candidate ears in a queue.
class EarClipper {
  public:
    explicit EarClipper(const std::vector<Vec<3>>& corners) : n_(corners.size()) {
        project(corners);
        prev_.resize(n_);
        next_.resize(n_);
        for (std::size_t i = 0; i < n_; ++i) {
            prev_[i] = std::uint32_t((i + n_ - 1) % n_);
            next_[i] = std::uint32_t((i + 1) % n_);
        }
        build_grid();
        removed_.assign(n_, 0);
        max_work_ = std::max<std::uint64_t>(200'000'000, 64 * std::uint64_t(n_));
        version_.assign(n_, 0);
    }

    // The triangles, or none when the work ran past its bound.
    std::vector<Triangle> clip() {
        std::vector<Triangle> triangles;
        triangles.reserve(n_ - 2);
        for (std::uint32_t v = 0; v < n_; ++v)
            consider(v);
        std::size_t left = n_;
        std::uint32_t live = 0; // a corner not clipped
        bool requeued = false;
        while (left > 3 && blockers_ > 0) {
            if (work_ > max_work_)
                return {};
            if (queue_.empty()) {
                // A corner whose ear held a reflex corner that has since
                // turned convex was dropped: queue every corner again, once.
                // No ear in all of them: the outline crosses itself, and is
                // no simple polygon; the rest is split as a fan, and the
                // solid check says what is wrong with it.
                if (requeued)
                    break;
                requeued = true;
                work_ += left;
                std::uint32_t v = live;
                do {
                    consider(v);
                    v = next_[v];
                } while (v != live);
                continue;
            }
            const auto [size, v, queued] = queue_.top();
            queue_.pop();
            if (removed_[v] || queued != version_[v])
                continue;
            const std::uint32_t a = prev_[v], c = next_[v];
            if (!is_ear(a, v, c))
                continue;
            triangles.push_back({a, v, c});
            removed_[v] = 1;
            next_[a] = c;
            prev_[c] = a;
            --left;
            live = a;
            requeued = false;
            for (const std::uint32_t k : {a, c})
                update_corner(k);
        }
        const std::uint32_t v = live;
        // What is left is convex (no blocking corner) or no simple polygon: a fan.
        for (std::uint32_t b = next_[v]; left >= 3 && next_[b] != v; b = next_[b], --left)
            triangles.push_back({v, b, next_[b]});
        return triangles;
    }

  private:
    // Projects the polygon on the plane its Newell normal is most nearly
    // along, the axes ordered so that it turns counter-clockwise.
    void project(const std::vector<Vec<3>>& corners) {
        // Newell's normal, about the first corner so that far-off polygons
        // keep their digits.
        Vec<3> normal(0);
        for (std::size_t i = 0; i < n_; ++i)
            normal += glm::cross(corners[i] - corners[0], corners[(i + 1) % n_] - corners[0]);
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (std::abs(normal[a]) > std::abs(normal[axis]))
                axis = a;
        int ax = (axis + 1) % 3, ay = (axis + 2) % 3;
        if (normal[axis] < 0)
            std::swap(ax, ay);
        p_.resize(n_);
        for (std::size_t i = 0; i < n_; ++i)
            p_[i] = {double(corners[i][ax] - corners[0][ax]),
                     double(corners[i][ay] - corners[0][ay])};
    }

    double turn(std::size_t a, std::size_t b, std::size_t c) const {
        return (p_[b][0] - p_[a][0]) * (p_[c][1] - p_[b][1]) -
               (p_[b][1] - p_[a][1]) * (p_[c][0] - p_[b][0]);
    }

    // Corners that are not strictly convex (reflex, or on a straight line)
    // may block an ear; they go into the grid.
    void build_grid() {
        blocking_.assign(n_, 0);
        for (int a = 0; a < 2; ++a)
            lo_[a] = hi_[a] = p_[0][a];
        for (std::size_t i = 0; i < n_; ++i) {
            blocking_[i] = !(turn(prev_[i], i, next_[i]) > 0);
            blockers_ += std::size_t(blocking_[i]);
            for (int a = 0; a < 2; ++a) {
                lo_[a] = std::min(lo_[a], p_[i][a]);
                hi_[a] = std::max(hi_[a], p_[i][a]);
            }
        }
        side_ = std::clamp<std::size_t>(std::size_t(std::sqrt(double(blockers_))), 1, 512);
        for (int a = 0; a < 2; ++a)
            width_[a] = std::max(hi_[a] - lo_[a], 1e-300);
        grid_.assign(side_ * side_, {});
        for (std::size_t i = 0; i < n_; ++i)
            if (blocking_[i])
                grid_[cell(i)].push_back(std::uint32_t(i));
    }

    std::size_t cell_of(double x, int a) const {
        const double c = (x - lo_[a]) / width_[a] * double(side_);
        return std::size_t(std::clamp(c, 0.0, double(side_ - 1)));
    }
    std::size_t cell(std::size_t i) const {
        return cell_of(p_[i][1], 1) * side_ + cell_of(p_[i][0], 0);
    }

    // a b c is an ear: convex, and no blocking corner inside or on it.
    bool is_ear(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        if (!(turn(a, b, c) > 0))
            return false;
        const double x0 = std::min({p_[a][0], p_[b][0], p_[c][0]}),
                     x1 = std::max({p_[a][0], p_[b][0], p_[c][0]});
        const double y0 = std::min({p_[a][1], p_[b][1], p_[c][1]}),
                     y1 = std::max({p_[a][1], p_[b][1], p_[c][1]});
        for (std::size_t cy = cell_of(y0, 1); cy <= cell_of(y1, 1); ++cy)
            for (std::size_t cx = cell_of(x0, 0); cx <= cell_of(x1, 0); ++cx) {
                const auto& in_cell = grid_[cy * side_ + cx];
                work_ += 1 + in_cell.size();
                for (const std::uint32_t k : in_cell) {
                    if (removed_[k] || !blocking_[k] || k == a || k == b || k == c ||
                        p_[k] == p_[a] || p_[k] == p_[b] || p_[k] == p_[c])
                        continue;
                    // Inside or on the ear's edges: the ear would cross the outline.
                    if (turn(a, b, k) >= 0 && turn(b, c, k) >= 0 && turn(c, a, k) >= 0)
                        return false;
                }
            }
        return true;
    }

    double squared(std::uint32_t i, std::uint32_t j) const {
        const double dx = p_[i][0] - p_[j][0], dy = p_[i][1] - p_[j][1];
        return dx * dx + dy * dy;
    }

    // Queues corner v's ear, if v is convex, by its longest side.
    void consider(std::uint32_t v) {
        ++version_[v];
        if (!blocking_[v])
            queue_.emplace(
                std::max({squared(prev_[v], v), squared(v, next_[v]), squared(next_[v], prev_[v])}),
                v, version_[v]);
    }

    // After an ear is clipped beside k. In a simple polygon a neighbour of
    // an ear only grows more convex; in one that crosses itself it may turn
    // reflex.
    void update_corner(std::uint32_t k) {
        const bool blocks = !(turn(prev_[k], k, next_[k]) > 0);
        if (blocks && !blocking_[k])
            grid_[cell(k)].push_back(k);
        if (blocks != bool(blocking_[k]))
            blockers_ = blocks ? blockers_ + 1 : blockers_ - 1;
        blocking_[k] = char(blocks);
        consider(k);
    }

    std::size_t n_;
    std::vector<std::array<double, 2>> p_;
    std::vector<std::uint32_t> prev_, next_;
    std::vector<char> blocking_, removed_;
    std::size_t blockers_ = 0;
    double lo_[2] = {}, hi_[2] = {}, width_[2] = {};
    std::size_t side_ = 1;
    std::vector<std::vector<std::uint32_t>> grid_;
    // Long thin ears (a fan across the polygon) can still make it quadratic:
    // past this many cells and corners looked at, it gives up (about a
    // second) and the face is refused rather than read for minutes.
    std::uint64_t work_ = 0, max_work_ = 0;
    // Candidate ears, the smallest first: clipping small ears walks along
    // the outline (a ladder down a long strip), where walking round it from
    // one corner fans out from it, each ear longer and its box over more of
    // the grid. An entry is stale once its corner is clipped or queued anew.
    using Candidate = std::tuple<double, std::uint32_t, std::uint32_t>; // size, corner, version
    std::priority_queue<Candidate, std::vector<Candidate>, std::greater<>> queue_;
    std::vector<std::uint32_t> version_;
};

} // namespace

// Splits one polygon into triangles by ear clipping (Meisters' two-ears
// theorem: a simple polygon of more than three corners has two
// non-overlapping ears), in the plane the polygon's Newell normal is most
// nearly along. Only reflex corners can lie inside an ear, so only they are
// tested, found through a uniform grid: a polygon of n corners takes about
// n ear tests of a few grid cells each, where testing every corner against
// every ear (tinyobjloader's way) took minutes for 200,000 corners.
std::vector<Triangle> split_polygon(const std::vector<Vec<3>>& corners) {
    if (corners.size() < 3)
        return {};
    return EarClipper(corners).clip();
}

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
    const ObjLines lines = scan_obj_lines(text, fail);

    tinyobj::ObjReaderConfig config;
    config.triangulate = true;
    config.vertex_color = false;
    tinyobj::ObjReader reader;
    // From memory with no material text: an `mtllib` line opens nothing.
    if (!reader.ParseFromString(lines.triangles_only, "", config))
        fail(fmt::format("not a readable OBJ file ({})", reader.Error()));

    const std::vector<tinyobj::real_t>& coordinates = reader.GetAttrib().vertices;
    check_vertices(coordinates, scale, offset, lines.vertices, fail);
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
    // The polygons, split here. Corners repeated at once (after joining)
    // are one corner.
    for (const PolygonLine& polygon : lines.polygons) {
        std::vector<std::uint32_t> ids;
        std::vector<Vec<3>> corners;
        for (const std::int64_t v : polygon.corners) {
            if (v < 0 || std::uint64_t(v) >= vertices.size())
                fail(fmt::format("line {}: the face names vertex {}, but the file has {} "
                                 "vertices",
                                 polygon.line, v + 1, vertices.size()));
            const std::uint32_t id = joined[std::size_t(v)];
            if (ids.empty() || id != ids.back()) {
                ids.push_back(id);
                corners.push_back(vertices[id]);
            }
        }
        if (ids.size() > 1 && ids.front() == ids.back()) {
            ids.pop_back();
            corners.pop_back();
        }
        const std::vector<Triangle> split = split_polygon(corners);
        if (split.empty() && corners.size() >= 3)
            fail(fmt::format("line {}: a face of {} corners too irregular to split into "
                             "triangles in reasonable time; split it in the modeller",
                             polygon.line, corners.size()));
        for (const Triangle& t : split)
            triangles.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
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
