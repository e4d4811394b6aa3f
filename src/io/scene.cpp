#include "io/scene.hpp"

#include "io/files.hpp"
#include "io/input_error.hpp"
#include "io/obj_mesh.hpp"
#include "io/scene_paths.hpp"
#include "sph/kernels.hpp"
#include "sph/lattice.hpp"
#include "sph/neighbours/neighbour_search.hpp"
#include "sph/solvers/solver.hpp"
#include "sph/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>

namespace sph {

using nlohmann::json;

namespace {

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
    // Only suggest what is plausibly a typo.
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 2);
    std::string best;
    std::size_t best_distance = std::string::npos;
    for (const auto& c : candidates) {
        // The distance is at least the difference in length: a long hostile
        // word is not compared letter by letter with every key.
        const std::size_t shortest =
            std::max(word.size(), c.size()) - std::min(word.size(), c.size());
        if (shortest > limit)
            continue;
        const std::size_t d = edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best_distance <= limit ? best : std::string();
}

// Compact JSON text of `value`, stopped soon after `limit` characters: a huge
// or deeply nested value is neither serialised whole nor recursed into deeper
// than the limit (each level adds a bracket).
void append_short(const json& value, std::string& out, std::size_t limit) {
    if (!value.is_structured()) {
        // A --set string need not be UTF-8: replaced, not thrown on.
        out += value.dump(-1, ' ', false, json::error_handler_t::replace);
        return;
    }
    const bool array = value.is_array();
    out += array ? '[' : '{';
    for (auto it = value.begin(); it != value.end() && out.size() <= limit; ++it) {
        if (it != value.begin())
            out += ',';
        if (!array)
            out += json(it.key()).dump(-1, ' ', false, json::error_handler_t::replace) + ':';
        append_short(*it, out, limit);
    }
    out += array ? ']' : '}';
}

std::string describe(const json& value) {
    std::string text;
    append_short(value, text, 40);
    if (text.size() > 40)
        text = text.substr(0, 37) + "...";
    return fmt::format("{} ({})", value.type_name(), text);
}

// A string from the scene as messages quote it: a hostile one can be long.
std::string shortened(const std::string& text) {
    return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

// "fluid.blocks[3].min" -> "fluid.blocks[].min": the key's place in the schema.
// By hand, not std::regex (slow, and recursive per character): it runs for
// every key of every block.
std::string generic_path(const std::string& path) {
    std::string out;
    out.reserve(path.size());
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] == '[') {
            std::size_t end = i + 1;
            while (end < path.size() && path[end] >= '0' && path[end] <= '9')
                ++end;
            if (end > i + 1 && end < path.size() && path[end] == ']') {
                out += "[]";
                i = end;
                continue;
            }
        }
        out += path[i];
    }
    return out;
}

// "a.b" encloses "a.b", "a.b.c" and "a.b[2]".
bool encloses(const std::string& outer, const std::string& inner) {
    return inner.starts_with(outer) && (inner.size() == outer.size() ||
                                        inner[outer.size()] == '.' || inner[outer.size()] == '[');
}

std::string parent_of(const std::string& path) {
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? std::string() : path.substr(0, dot);
}

std::string last_segment(const std::string& path) {
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? path : path.substr(dot + 1);
}

std::string format_vector(const Vec3& v, int dimension) {
    return fmt::format("[{}]", fmt::join(v.begin(), v.begin() + dimension, ", "));
}

enum class Bound { any, positive, non_negative };

// Reads fields by dotted path with type and range checks. Every key it is
// asked for is recorded: the reading code is the schema, so the unknown-key
// check and `sphclip keys` cannot drift from it.
class FieldReader {
  public:
    FieldReader(const json& root, std::string file, std::set<std::string> overridden)
        : root_(root), file_(std::move(file)), overridden_(std::move(overridden)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        const bool from_command_line =
            std::any_of(overridden_.begin(), overridden_.end(), [&](const std::string& key) {
                return encloses(key, path) || encloses(path, key);
            });
        throw InputError(file_, path + (from_command_line ? " (from --set)" : ""), problem);
    }

    // nullptr when absent (or null).
    const json* find(const std::string& path) const {
        const json* node = &root_;
        std::size_t begin = 0;
        while (begin <= path.size()) {
            std::size_t end = path.find('.', begin);
            if (end == std::string::npos)
                end = path.size();
            std::string segment = path.substr(begin, end - begin);
            std::optional<std::size_t> index;
            if (auto bracket = segment.find('['); bracket != std::string::npos) {
                index = std::stoul(segment.substr(bracket + 1));
                segment.resize(bracket);
            }
            if (!node->is_object())
                return nullptr;
            auto it = node->find(segment);
            if (it == node->end() || it->is_null())
                return nullptr;
            node = &*it;
            if (index) {
                if (!node->is_array() || *index >= node->size())
                    return nullptr;
                node = &(*node)[*index];
            }
            begin = end + 1;
        }
        return node;
    }

    double number(const std::string& path, double fallback, const char* unit, const char* doc,
                  Bound bound = Bound::any) {
        record(path, "number", unit, fmt::format("{}", fallback), doc);
        const json* v = find(path);
        return v ? checked_number(path, *v, bound) : fallback;
    }

    std::optional<double> optional_number(const std::string& path, const char* unit,
                                          const std::string& default_text, const char* doc,
                                          Bound bound = Bound::any) {
        record(path, "number or null", unit, default_text, doc);
        const json* v = find(path);
        return v ? std::optional(checked_number(path, *v, bound)) : std::nullopt;
    }

    int integer(const std::string& path, int fallback, int min, int max, const char* doc) {
        record(path, "integer", "", std::to_string(fallback), doc);
        const json* v = find(path);
        return v ? checked_integer(path, *v, min, max) : fallback;
    }

    bool boolean(const std::string& path, bool fallback, const char* doc) {
        record(path, "true or false", "", fallback ? "true" : "false", doc);
        const json* v = find(path);
        if (!v)
            return fallback;
        if (!v->is_boolean())
            fail(path, "expected true or false, got " + describe(*v));
        return v->get<bool>();
    }

    std::string choice(const std::string& path, const std::string& fallback,
                       const std::vector<std::string>& allowed, const char* doc) {
        record(path, "string", "", fallback,
               fmt::format("{} One of: {}.", doc, fmt::join(allowed, ", ")));
        const json* v = find(path);
        if (!v)
            return fallback;
        if (!v->is_string())
            fail(path, "expected a string, got " + describe(*v));
        const auto text = v->get<std::string>();
        if (std::find(allowed.begin(), allowed.end(), text) == allowed.end()) {
            const auto guess = closest(text, allowed);
            fail(path,
                 fmt::format("unknown value \"{}\"{}; expected one of: {}", shortened(text),
                             guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                             fmt::join(allowed, ", ")));
        }
        return text;
    }

    std::optional<std::string> optional_text(const std::string& path,
                                             const std::string& default_text, const char* doc) {
        record(path, "string", "", default_text, doc);
        const json* v = find(path);
        if (!v)
            return std::nullopt;
        if (!v->is_string())
            fail(path, "expected a string, got " + describe(*v));
        return v->get<std::string>();
    }

    Vec3 vector(const std::string& path, const Vec3& fallback, int dimension, const char* unit,
                const char* doc) {
        record(path, fmt::format("array of {} numbers", dimension), unit,
               format_vector(fallback, dimension), doc);
        const json* v = find(path);
        return v ? checked_vector(path, *v, dimension) : fallback;
    }

    std::optional<Vec3> optional_vector(const std::string& path, int dimension, const char* unit,
                                        const std::string& default_text, const char* doc) {
        record(path, fmt::format("array of {} numbers or null", dimension), unit, default_text,
               doc);
        const json* v = find(path);
        return v ? std::optional(checked_vector(path, *v, dimension)) : std::nullopt;
    }

    std::array<int, 2> image_size(const std::string& path, std::array<int, 2> fallback,
                                  const char* doc) {
        record(path, "array of 2 integers", "px", fmt::format("[{}, {}]", fallback[0], fallback[1]),
               doc);
        const json* v = find(path);
        if (!v)
            return fallback;
        if (!v->is_array() || v->size() != 2)
            fail(path, "expected an array of 2 integers [width, height], got " + describe(*v));
        return {checked_integer(path, (*v)[0], 1, 16384), checked_integer(path, (*v)[1], 1, 16384)};
    }

    // A list of objects; returns the element count (0 when absent).
    std::size_t list(const std::string& path, const std::string& default_text, const char* doc) {
        record(path, "array of objects", "", default_text, doc);
        const json* v = find(path);
        if (!v)
            return 0;
        if (!v->is_array())
            fail(path, "expected an array, got " + describe(*v));
        for (std::size_t i = 0; i < v->size(); ++i)
            if (!(*v)[i].is_object())
                fail(fmt::format("{}[{}]", path, i),
                     "expected an object, got " + describe((*v)[i]));
        return v->size();
    }

    bool present(const std::string& path) const { return find(path) != nullptr; }

    bool is_object_key(const std::string& path) const {
        const auto prefix = path + ".";
        return std::any_of(known_.begin(), known_.end(),
                           [&](const std::string& k) { return k.starts_with(prefix); });
    }

    // Names the first key in the scene that no reader asked for.
    void reject_unknown_keys() const { check_object(root_, ""); }

    const std::vector<KeyDoc>& docs() const { return docs_; }

  private:
    void record(const std::string& path, std::string type, const std::string& unit,
                std::string default_value, std::string doc) {
        const auto generic = generic_path(path);
        if (known_.insert(generic).second)
            docs_.push_back(
                {generic, std::move(type), unit, std::move(default_value), std::move(doc)});
    }

    double checked_number(const std::string& path, const json& v, Bound bound) const {
        if (!v.is_number())
            fail(path, "expected a number, got " + describe(v));
        const double x = v.get<double>();
        if (!std::isfinite(x))
            fail(path, "expected a finite number");
        if (bound == Bound::positive && !(x > 0))
            fail(path, fmt::format("must be greater than 0, got {}", x));
        if (bound == Bound::non_negative && x < 0)
            fail(path, fmt::format("must not be negative, got {}", x));
        return x;
    }

    int checked_integer(const std::string& path, const json& v, int min, int max) const {
        if (!v.is_number())
            fail(path, "expected an integer, got " + describe(v));
        const double x = v.get<double>();
        if (x != std::floor(x))
            fail(path, fmt::format("expected an integer, got {}", x));
        if (x < min || x > max)
            fail(path, fmt::format("must be between {} and {}, got {}", min, max, x));
        return static_cast<int>(x);
    }

    Vec3 checked_vector(const std::string& path, const json& v, int dimension) const {
        if (!v.is_array() || static_cast<int>(v.size()) != dimension)
            fail(path, fmt::format("expected an array of {} numbers (the scene is {}D), got {}",
                                   dimension, dimension, describe(v)));
        Vec3 out{0, 0, 0};
        for (int a = 0; a < dimension; ++a) {
            const std::string element = fmt::format("{}[{}]", path, a);
            if (!v[a].is_number())
                fail(element, "expected a number, got " + describe(v[a]));
            out[a] = v[a].get<double>();
            if (!std::isfinite(out[a]))
                fail(element, "expected a finite number");
        }
        return out;
    }

    void check_object(const json& object, const std::string& prefix) const {
        for (auto it = object.begin(); it != object.end(); ++it) {
            const std::string path = prefix.empty() ? it.key() : prefix + "." + it.key();
            if (it.key().find_first_of("[]") != std::string::npos)
                reject(path, path); // brackets only ever come from list indices
            const std::string generic = generic_path(path);
            if (known_.contains(generic)) {
                if (it->is_array() && is_list(generic))
                    for (std::size_t i = 0; i < it->size(); ++i)
                        check_object((*it)[i], fmt::format("{}[{}]", path, i));
                continue;
            }
            if (is_object_key(generic)) {
                if (it->is_object())
                    check_object(*it, path);
                else if (!it->is_null())
                    fail(path, "expected an object, got " + describe(*it));
                continue;
            }
            reject(path, generic);
        }
    }

    bool is_list(const std::string& generic) const {
        const auto prefix = generic + "[].";
        return std::any_of(known_.begin(), known_.end(),
                           [&](const std::string& k) { return k.starts_with(prefix); });
    }

    [[noreturn]] void reject(const std::string& path, const std::string& generic) const {
        // Suggest among the keys beside it first, then anywhere in the scene.
        const std::string parent = parent_of(generic);
        std::vector<std::string> siblings, all;
        for (const auto& k : known_) {
            all.push_back(k);
            if (parent_of(k) == parent)
                siblings.push_back(last_segment(k));
        }
        for (const auto& k : known_) // groups are keys too
            for (std::string p = parent_of(k); !p.empty(); p = parent_of(p))
                if (parent_of(p) == parent)
                    siblings.push_back(last_segment(p));
        std::string guess = closest(last_segment(generic), siblings);
        if (!guess.empty())
            guess = parent.empty() ? guess : parent_of(path) + "." + guess;
        else
            guess = closest(generic, all);
        fail(path, "unknown key" + (guess.empty() ? std::string()
                                                  : fmt::format(" (did you mean '{}'?)", guess)));
    }

    const json& root_;
    std::string file_;
    std::set<std::string> overridden_;
    std::set<std::string> known_;
    std::vector<KeyDoc> docs_;
};

// Sets root[path] = value for `--set path=value`, creating objects on the way.
void apply_override(json& root, const Override& o, const std::string& file) {
    const std::string field = o.key + " (from --set)";
    if (o.key.empty())
        throw InputError(file, "--set", "expected KEY=VALUE, got an empty key");
    // JSON when it parses as JSON, else the text itself as a string.
    json value;
    try {
        value = json::parse(o.value);
    } catch (const json::out_of_range&) {
        throw InputError(file, field, fmt::format("the number {} is out of range", o.value));
    } catch (const json::exception&) {
        value = o.value;
    }
    json* node = &root;
    std::size_t begin = 0;
    while (true) {
        std::size_t end = o.key.find('.', begin);
        const bool last = end == std::string::npos;
        if (last)
            end = o.key.size();
        const std::string segment = o.key.substr(begin, end - begin);
        if (segment.empty())
            throw InputError(file, field, "empty segment in the key");
        if (node->is_array()) {
            // A numeric segment indexes a list: fluid.blocks.0.min=[...]
            if (!std::all_of(segment.begin(), segment.end(), ::isdigit))
                throw InputError(file, field,
                                 fmt::format("'{}' is a list; index it with a number",
                                             o.key.substr(0, begin - 1)));
            const std::size_t index = std::stoul(segment);
            if (index > node->size())
                throw InputError(
                    file, field,
                    fmt::format("index {} is past the end of a list of {}", index, node->size()));
            if (index == node->size())
                node->push_back(last ? json() : json::object());
            node = &(*node)[index];
        } else {
            if (node->is_null())
                *node = json::object();
            if (!node->is_object())
                throw InputError(file, field,
                                 fmt::format("'{}' is not an object", o.key.substr(0, begin - 1)));
            json& child = (*node)[segment];
            if (!last && child.is_null()) {
                // fluid.blocks.0.min on a scene without a blocks list creates the list.
                const std::size_t next_end = o.key.find('.', end + 1);
                const std::string next =
                    o.key.substr(end + 1, next_end == std::string::npos ? std::string::npos
                                                                        : next_end - end - 1);
                if (!next.empty() && std::all_of(next.begin(), next.end(), ::isdigit))
                    child = json::array();
            }
            node = &child;
        }
        if (last)
            break;
        begin = end + 1;
    }
    *node = std::move(value);
}

std::string override_path(const std::string& key) {
    // fluid.blocks.0.min -> fluid.blocks[0].min, the form messages use.
    static const std::regex index(R"(\.(\d+)(?=\.|$))");
    return std::regex_replace(key, index, "[$1]");
}

// The limits a scene is checked against (docs/scenes.md, "Fluid blocks").
const std::filesystem::path output_root = "out";
constexpr double max_frames = 1e7;
constexpr double max_support = 20;      // h in spacings
constexpr double max_particles = 4.0e9; // fluid or boundary; indices are 32-bit

double neighbours_within(int dimension, double radius) {
    return dimension == 2 ? M_PI * radius * radius : 4.0 / 3.0 * M_PI * std::pow(radius, 3);
}

// solver.kernel, "auto" resolved.
std::string derive_kernel(const Scene& s) {
    return s.solver.kernel != "auto" ? s.solver.kernel
           : s.solver.name == "seed" ? "seed"
                                     : "cubic_spline";
}

double default_smoothing_ratio(int dimension) {
    return dimension == 2 ? 2.5 : 2.2;
}

// Rough memory of one particle: state, neighbour list, hash lookup, snapshot.
double bytes_per_particle(int dimension, double smoothing_ratio) {
    const double neighbours = neighbours_within(dimension, smoothing_ratio);
    return 3 * dimension * 8 + 2 * 8 + 4 + 4 * neighbours + 4 + 8 + 4 + 2 * dimension * 8 + 2 * 8 +
           4;
}

double physical_memory_bytes() {
    const long pages = sysconf(_SC_PHYS_PAGES);
    const long page_size = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page_size > 0 ? double(pages) * double(page_size) : 0;
}

// effects.obstacles: each element a box, a sphere or (3D) a mesh. With no
// list the keys are still read, for the documentation. A mesh's OBJ file is
// read here, relative to the scene file's folder; checks against the domain
// and the spacing come with the other checks of several fields.
void read_obstacles(FieldReader& r, int dim, const std::string& file,
                    std::vector<SceneObstacle>& obstacles) {
    const std::size_t count =
        r.list("effects.obstacles", "none",
               "Static obstacles the fluid flows around (wcsph, dfsph): each {\"box\": {...}}, "
               "{\"sphere\": {...}} or (3D) {\"mesh\": {...}}, made of boundary particles.");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.obstacles[{}]", i);
        const auto min = r.optional_vector(p + ".box.min", dim, "m", "required",
                                           "Lower corner of a box obstacle.");
        const auto max = r.optional_vector(p + ".box.max", dim, "m", "required",
                                           "Upper corner of a box obstacle.");
        const auto centre = r.optional_vector(p + ".sphere.centre", dim, "m", "required",
                                              "Centre of a sphere obstacle (a circle in 2D).");
        const auto radius = r.optional_number(p + ".sphere.radius", "m", "required",
                                              "Radius of a sphere obstacle.", Bound::positive);
        const json* box = r.find(p + ".box");
        const json* sphere = r.find(p + ".sphere");
        const json* mesh = r.find(p + ".mesh");
        if (i < count && mesh && dim == 2)
            r.fail(p + ".mesh", "a mesh obstacle is a 3D solid; a 2D scene has boxes and spheres "
                                "(circles) only");
        const auto mesh_file = r.optional_text(
            p + ".mesh.file", "required",
            "Wavefront OBJ file of a closed triangle mesh obstacle (3D only), relative to the "
            "scene file's folder (not absolute, no \"..\").");
        const double mesh_scale =
            r.number(p + ".mesh.scale", 1, "m per file unit",
                     "Scale of a mesh obstacle: a vertex v of the file is at scale v + offset.",
                     Bound::positive);
        // Always 3 numbers: a mesh is 3D (a 2D scene was refused above).
        const Vec3 mesh_offset = r.vector(p + ".mesh.offset", {0, 0, 0}, 3, "m",
                                          "Offset of a mesh obstacle, added after scaling.");
        if (i >= count)
            break;
        SceneObstacle o;
        const int shapes = (box != nullptr) + (sphere != nullptr) + (mesh != nullptr);
        if (shapes != 1)
            r.fail(p, shapes > 1 ? "an obstacle is one of box, sphere or mesh, not several"
                                 : "expected {\"box\": {\"min\": [...], \"max\": [...]}}, "
                                   "{\"sphere\": {\"centre\": [...], \"radius\": r}} or (3D) "
                                   "{\"mesh\": {\"file\": \"name.obj\"}}");
        const json* given = box ? box : sphere ? sphere : mesh;
        const std::string shape = p + (box ? ".box" : sphere ? ".sphere" : ".mesh");
        if (!given->is_object())
            r.fail(shape, "expected an object, got " + describe(*given));
        if (box) {
            if (!min || !max)
                r.fail(shape + (min ? ".max" : ".min"), "a box obstacle needs min and max");
            o.shape = ObstacleShape::box;
            o.min = *min;
            o.max = *max;
        } else if (sphere) {
            if (!centre || !radius)
                r.fail(shape + (centre ? ".radius" : ".centre"),
                       "a sphere obstacle needs centre and radius");
            o.shape = ObstacleShape::sphere;
            o.centre = *centre;
            o.radius = *radius;
        } else {
            if (!mesh_file)
                r.fail(shape + ".file", "a mesh obstacle needs the OBJ file's name");
            o.shape = ObstacleShape::mesh;
            o.mesh_file = *mesh_file;
            o.mesh_scale = mesh_scale;
            o.mesh_offset = mesh_offset;
            // Relative to the scene's own folder, and inside it, as a scene
            // from elsewhere must not read files outside it.
            const std::filesystem::path folder = std::filesystem::path(file).parent_path();
            try {
                const std::filesystem::path path = resolve_inside(
                    folder.empty() ? "." : folder, *mesh_file, file, shape + ".file");
                o.mesh = read_obj_mesh(path, mesh_scale,
                                       {mesh_offset[0], mesh_offset[1], mesh_offset[2]}, file,
                                       shape + ".file");
            } catch (const InputError& e) {
                r.fail(e.field, e.problem);
            }
        }
        obstacles.push_back(o);
    }
}

// effects.emitters: each a box, a velocity and a time window.
void read_emitters(FieldReader& r, int dim, std::vector<SceneEmitter>& emitters) {
    const std::size_t count = r.list(
        "effects.emitters", "none",
        "Streams of fluid entering the domain: each box is filled on the fluid's lattice and "
        "emitted whole every (its thickness along velocity) / |velocity| seconds.");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.emitters[{}]", i);
        const SceneEmitter fallback;
        SceneEmitter e;
        e.min = r.vector(p + ".min", fallback.min, dim, "m", "Lower corner of the emitter's box.");
        e.max = r.vector(p + ".max", fallback.max, dim, "m", "Upper corner of the emitter's box.");
        e.velocity = r.vector(p + ".velocity", fallback.velocity, dim, "m/s",
                              "Velocity of the emitted particles (not zero).");
        e.start = r.number(p + ".start", fallback.start, "s", "When the emitter starts.",
                           Bound::non_negative);
        e.end = r.number(p + ".end", fallback.end, "s", "When the emitter stops.",
                         Bound::non_negative);
        e.radius = r.optional_number(
            p + ".radius", "m", "the whole box",
            "A disc inlet (a round pipe in 3D): only the box's lattice sites within this "
            "distance of the axis through its centre along velocity are emitted.",
            Bound::positive);
        if (i >= count)
            break;
        double speed = 0;
        for (int a = 0; a < dim; ++a)
            speed += e.velocity[a] * e.velocity[a];
        if (!(speed > 0))
            r.fail(p + ".velocity", "an emitter needs a velocity that is not zero");
        if (!(e.start < e.end))
            r.fail(p + ".end", "must be after start");
        emitters.push_back(e);
    }
}

// effects.paddles: each a box with a prescribed motion, sine (a piston
// wavemaker) or linear (a piston pushing at constant speed). Checks against
// the domain and the spacing come with the other checks of several fields.
void read_paddles(FieldReader& r, int dim, std::vector<ScenePaddle>& paddles) {
    const std::size_t count = r.list(
        "effects.paddles", "none",
        "Boxes that move with a prescribed motion (wcsph, dfsph), a piston wavemaker: made of "
        "boundary particles that push the fluid and drag it along (no slip).");
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("effects.paddles[{}]", i);
        const ScenePaddle fallback;
        ScenePaddle o;
        o.min = r.vector(p + ".min", fallback.min, dim, "m",
                         "Lower corner of the paddle's box at rest (before start).");
        o.max = r.vector(p + ".max", fallback.max, dim, "m",
                         "Upper corner of the paddle's box at rest.");
        o.motion = r.choice(p + ".motion", fallback.motion, {"sine", "linear"},
                            "How the paddle moves from start on: sine, displacement amplitude "
                            "sin(2 pi (t - start) / period); linear, velocity (t - start) until "
                            "end, then it stays.");
        o.amplitude = r.vector(p + ".amplitude", fallback.amplitude, dim, "m",
                               "Sine: the largest displacement (half the stroke), as a vector "
                               "along the motion.");
        o.period =
            r.number(p + ".period", fallback.period, "s", "Sine: the period.", Bound::positive);
        o.velocity = r.vector(p + ".velocity", fallback.velocity, dim, "m/s",
                              "Linear: the velocity (not zero).");
        o.start = r.number(p + ".start", fallback.start, "s", "When the paddle starts moving.",
                           Bound::non_negative);
        o.end = r.number(p + ".end", fallback.end, "s", "Linear: when the paddle stops.",
                         Bound::non_negative);
        if (i >= count)
            break;
        // Keys of the other motion would be silently ignored: refused instead.
        const bool sine = o.motion == "sine";
        for (const char* key : {".velocity", ".end"})
            if (sine && r.present(p + key))
                r.fail(p + key, "is for motion \"linear\"; a sine paddle has amplitude and period");
        for (const char* key : {".amplitude", ".period"})
            if (!sine && r.present(p + key))
                r.fail(p + key, "is for motion \"sine\"; a linear paddle has velocity and end");
        if (!sine) {
            double speed = 0;
            for (int a = 0; a < dim; ++a)
                speed += o.velocity[a] * o.velocity[a];
            if (!(speed > 0))
                r.fail(p + ".velocity", "a linear paddle needs a velocity that is not zero");
            if (!(o.start < o.end))
                r.fail(p + ".end", "must be after start");
        }
        paddles.push_back(o);
    }
}

// Checks obstacle i against the domain and the spacing. Returns an upper
// bound on the boundary particles its shell takes (sph/obstacles.cpp), in
// floating point like the blocks' counts.
double check_obstacle(const FieldReader& r, const Scene& s, std::size_t i, double layers) {
    const SceneObstacle& o = s.effects.obstacles[i];
    const int dim = s.dimension;
    const double spacing = s.fluid.spacing;
    const std::string p = fmt::format("effects.obstacles[{}]", i);
    auto outside = [&](double lo, double hi, int a) {
        const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
        return lo < s.domain.min[a] - tolerance || hi > s.domain.max[a] + tolerance;
    };
    if (o.shape == ObstacleShape::box) {
        double sites = 1, interior = 1;
        for (int a = 0; a < dim; ++a) {
            if (!(o.min[a] < o.max[a]))
                r.fail(p + ".box",
                       fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                   "xyz"[a], o.min[a], o.max[a]));
            if (outside(o.min[a], o.max[a], a))
                r.fail(p + ".box",
                       fmt::format("the box [{}, {}] on axis {} is outside the domain [{}, {}]",
                                   o.min[a], o.max[a], "xyz"[a], s.domain.min[a], s.domain.max[a]));
            const double along = (o.max[a] - o.min[a]) / spacing;
            if (!(along >= 1 - 1e-9))
                r.fail(p + ".box",
                       fmt::format("the box is thinner than one spacing ({} m) on axis {}: too "
                                   "thin a solid for the fluid to see",
                                   spacing, "xyz"[a]));
            sites *= std::max(1.0, std::round(along));
            interior *= std::max(0.0, std::round(along) - 2 * layers);
        }
        return sites - interior;
    }
    if (o.shape == ObstacleShape::mesh) {
        // The mesh's bounding box, as a box obstacle's own.
        const Box<3>& bounds = o.mesh->bounds();
        double sites = 1;
        for (int a = 0; a < dim; ++a) {
            if (outside(bounds.min[a], bounds.max[a], a))
                r.fail(p + ".mesh",
                       fmt::format("the mesh (scaled and moved) spans [{}, {}] on axis {}, outside "
                                   "the domain [{}, {}]",
                                   bounds.min[a], bounds.max[a], "xyz"[a], s.domain.min[a],
                                   s.domain.max[a]));
            const double along = (bounds.max[a] - bounds.min[a]) / spacing;
            if (!(along >= 1 - 1e-9))
                r.fail(p + ".mesh",
                       fmt::format("the mesh (scaled) is thinner than one spacing ({} m) on axis "
                                   "{}: too thin a solid for the fluid to see",
                                   spacing, "xyz"[a]));
            sites *= std::max(1.0, std::round(along));
        }
        // The shell is about its area times its depth; twice that allows for
        // curvature and the lattice, and no more than its bounding box holds.
        return std::min(sites, 2 * o.mesh->area() / (spacing * spacing) * layers + 1);
    }
    for (int a = 0; a < dim; ++a)
        if (outside(o.centre[a], o.centre[a], a))
            r.fail(p + ".sphere.centre",
                   fmt::format("{} on axis {} is outside the domain [{}, {}]", o.centre[a],
                               "xyz"[a], s.domain.min[a], s.domain.max[a]));
    if (!(2 * o.radius >= spacing * (1 - 1e-9)))
        r.fail(p + ".sphere.radius",
               fmt::format("{} m is less than half a spacing ({} m): too small a solid for the "
                           "fluid to see",
                           o.radius, spacing));
    for (int a = 0; a < dim; ++a)
        if (outside(o.centre[a] - o.radius, o.centre[a] + o.radius, a))
            r.fail(p + ".sphere.radius",
                   fmt::format("the sphere reaches outside the domain on axis {} ([{}, {}] against "
                               "[{}, {}])",
                               "xyz"[a], o.centre[a] - o.radius, o.centre[a] + o.radius,
                               s.domain.min[a], s.domain.max[a]));
    const double around = dim == 2 ? 2 * M_PI * o.radius / spacing
                                   : 4 * M_PI * o.radius * o.radius / (spacing * spacing);
    return layers * (around + 1);
}

// Checks paddle i: its box at rest as an obstacle's box, and the room its
// motion sweeps over the clip inside the domain. Returns the boundary
// particles of its shell.
double check_paddle(const FieldReader& r, const Scene& s, std::size_t i, double layers) {
    const ScenePaddle& o = s.effects.paddles[i];
    const int dim = s.dimension;
    const std::string p = fmt::format("effects.paddles[{}]", i);
    const bool sine = o.motion == "sine";
    // How far the motion takes the box from rest over the clip, per axis.
    const double moving = std::max(0.0, std::min(o.end, s.duration) - o.start);
    double sites = 1, interior = 1;
    for (int a = 0; a < dim; ++a) {
        if (!(o.min[a] < o.max[a]))
            r.fail(p, fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                  "xyz"[a], o.min[a], o.max[a]));
        const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
        auto outside = [&](double lo, double hi) {
            return lo < s.domain.min[a] - tolerance || hi > s.domain.max[a] + tolerance;
        };
        if (outside(o.min[a], o.max[a]))
            r.fail(p, fmt::format("the paddle's box [{}, {}] on axis {} is outside the domain "
                                  "[{}, {}]",
                                  o.min[a], o.max[a], "xyz"[a], s.domain.min[a], s.domain.max[a]));
        const double travel = sine ? 0 : o.velocity[a] * moving;
        const double back = sine ? std::abs(o.amplitude[a]) : std::max(0.0, -travel);
        const double forth = sine ? std::abs(o.amplitude[a]) : std::max(0.0, travel);
        if (outside(o.min[a] - back, o.max[a] + forth))
            r.fail(p + (sine ? ".amplitude" : ".velocity"),
                   fmt::format("moves the paddle outside the domain on axis {}: over the clip "
                               "it spans [{:.6g}, {:.6g}], against [{}, {}]",
                               "xyz"[a], o.min[a] - back, o.max[a] + forth, s.domain.min[a],
                               s.domain.max[a]));
        const double along = (o.max[a] - o.min[a]) / s.fluid.spacing;
        if (!(along >= 1 - 1e-9))
            r.fail(p, fmt::format("the paddle is thinner than one spacing ({} m) on axis {}: too "
                                  "thin a solid for the fluid to see",
                                  s.fluid.spacing, "xyz"[a]));
        sites *= std::max(1.0, std::round(along));
        interior *= std::max(0.0, std::round(along) - 2 * layers);
    }
    return sites - interior;
}

// The viscosity effects. Viscosity is a property of the fluid, so a scene
// that gives material.viscosity > 0 gets the solver's model for it without
// naming an effect (the seed's term for seed, Morris's for the others);
// effects.viscosity chooses the model and may give mu itself. Likewise wcsph
// keeps solver.artificial_viscosity unless effects.artificial_viscosity says
// otherwise. A coefficient of 0 means the effect is not in the step.
void read_viscosity_effects(FieldReader& r, Scene& s) {
    const std::string default_model = s.solver.name == "seed" ? "seed" : "morris";
    const std::string model = r.choice(
        "effects.viscosity.model", "seed for the seed solver, morris for the others",
        {"seed", "morris"},
        "Viscosity effect: seed (the report's term, Müller et al. 2003) or morris (Morris et "
        "al. 1997, laminar, suited to very viscous fluids, no-slip walls).");
    const double mu = r.number("effects.viscosity.mu", s.material.viscosity, "Pa.s",
                               "Viscosity effect: dynamic viscosity; default material.viscosity.",
                               Bound::non_negative);
    if (r.present("effects.viscosity")) {
        const bool model_given = r.present("effects.viscosity.model");
        if (mu > 0)
            s.effects.viscosity = {model_given ? model : default_model, mu};
    } else if (s.material.viscosity > 0) {
        s.effects.viscosity = {default_model, s.material.viscosity};
    }
    const double alpha =
        r.number("effects.artificial_viscosity.alpha", s.solver.artificial_viscosity, "",
                 "Artificial viscosity effect (Monaghan 1992), its alpha; default "
                 "solver.artificial_viscosity. Without the key, wcsph uses "
                 "solver.artificial_viscosity and the other solvers none.",
                 Bound::non_negative);
    if (r.present("effects.artificial_viscosity")) {
        if (alpha > 0)
            s.effects.artificial_viscosity = alpha;
    } else if (s.solver.name == "wcsph" && s.solver.artificial_viscosity > 0) {
        s.effects.artificial_viscosity = s.solver.artificial_viscosity;
    }
    const double epsilon = r.number(
        "effects.xsph.epsilon", 0.5, "",
        "XSPH velocity smoothing effect (Monaghan 1989): each step draws a particle's "
        "velocity this fraction of the way to its neighbours' mean; in (0, 1]. Absent: none.",
        Bound::positive);
    if (epsilon > 1)
        r.fail("effects.xsph.epsilon",
               fmt::format("{} is above 1: XSPH would overshoot the neighbours' mean velocity",
                           epsilon));
    if (r.present("effects.xsph"))
        s.effects.xsph = epsilon;
}

Scene read_fields(const json& root, const std::string& file, std::set<std::string> overridden,
                  std::vector<KeyDoc>* docs) {
    FieldReader r(root, file, std::move(overridden));
    Scene s;
    s.file = file;
    const Scene d; // defaults

    s.dimension = r.integer("dimension", d.dimension, 2, 3, "Spatial dimension: 2 or 3.");
    const int dim = s.dimension;
    s.duration =
        r.number("duration", d.duration, "s", "Simulated time of the clip.", Bound::positive);
    s.fps = r.number("fps", d.fps, "1/s", "Frames per simulated second.", Bound::positive);

    s.domain.min =
        r.vector("domain.min", d.domain.min, dim, "m", "Lower corner of the walls' box.");
    s.domain.max =
        r.vector("domain.max", d.domain.max, dim, "m", "Upper corner of the walls' box.");

    s.fluid.spacing =
        r.number("fluid.spacing", d.fluid.spacing, "m",
                 "Lattice spacing of the particles in the fluid blocks.", Bound::positive);
    const std::size_t block_count = r.list("fluid.blocks", "one block, the dam-break column",
                                           "Boxes filled with fluid particles on the lattice.");
    if (r.present("fluid.blocks"))
        s.fluid.blocks.assign(block_count, FluidBlock{});
    for (std::size_t i = 0; i < std::max<std::size_t>(block_count, 1); ++i) {
        // With no list in the scene the default block is read (and documented).
        const std::string p = fmt::format("fluid.blocks[{}]", i);
        FluidBlock fallback = d.fluid.blocks[0];
        FluidBlock b;
        b.min = r.vector(p + ".min", fallback.min, dim, "m", "Lower corner of the block.");
        b.max = r.vector(p + ".max", fallback.max, dim, "m", "Upper corner of the block.");
        b.velocity = r.vector(p + ".velocity", fallback.velocity, dim, "m/s",
                              "Initial velocity of the block's particles.");
        if (i < s.fluid.blocks.size())
            s.fluid.blocks[i] = b;
    }
    s.fluid.smoothing_ratio =
        r.optional_number("fluid.smoothing_ratio", "", "2.5 (2D), 2.2 (3D)",
                          "Support radius h as a multiple of the spacing.", Bound::positive);
    s.fluid.smoothing_length = r.optional_number(
        "fluid.smoothing_length", "m", "ratio x spacing",
        "Support radius h of the kernels (the seed's interaction radius); overrides the ratio.",
        Bound::positive);
    s.fluid.mass = r.optional_number(
        "fluid.mass", "kg", "rest density on the lattice",
        "Mass of each particle; by default the mass that gives a lattice particle exactly the "
        "rest density.",
        Bound::positive);

    s.material.rest_density = r.number("material.rest_density", d.material.rest_density, "kg/m^3",
                                       "Rest density rho0.", Bound::positive);
    s.material.bulk_modulus =
        r.number("material.bulk_modulus", d.material.bulk_modulus, "Pa",
                 "Bulk modulus K of the linear law p = K (rho - rho0) / rho0; speed of sound "
                 "c = sqrt(K / rho0).",
                 Bound::positive);
    s.material.viscosity = r.number("material.viscosity", d.material.viscosity, "Pa.s",
                                    "Dynamic viscosity mu.", Bound::non_negative);

    s.solver.name = r.choice("solver.name", d.solver.name, solver_names(),
                             "Solver: seed (the report's model), wcsph (Becker & Teschner 2007) "
                             "or dfsph (Bender & Koschier 2017).");
    s.solver.kernel =
        r.choice("solver.kernel", d.solver.kernel, {"auto", "seed", "cubic_spline", "wendland_c2"},
                 "Smoothing kernel: seed (poly6 values, spiky gradients), "
                 "cubic_spline or wendland_c2; auto: seed for the seed solver, "
                 "cubic_spline for the others.");
    s.solver.dt = r.optional_number(
        "solver.dt", "s", "adaptive",
        "Fixed time step; without it the step adapts (solver.cfl, solver.dt_min, solver.dt_max).",
        Bound::positive);
    s.solver.cfl = r.number("solver.cfl", d.solver.cfl, "",
                            "Courant number of the adaptive step: dt <= cfl h / (c + v_max) for "
                            "seed and wcsph, dt <= cfl spacing / v_max for dfsph.",
                            Bound::positive);
    s.solver.dt_min =
        r.number("solver.dt_min", d.solver.dt_min, "s", "Smallest adaptive step.", Bound::positive);
    s.solver.dt_max =
        r.number("solver.dt_max", d.solver.dt_max, "s", "Largest adaptive step.", Bound::positive);
    s.solver.integrator =
        r.choice("solver.integrator", d.solver.integrator, {"symplectic_euler", "verlet"},
                 "Time integrator of seed and wcsph: symplectic_euler (first "
                 "order, the seed's) or verlet (kick-drift-kick, second order).");
    s.solver.walls = r.choice("solver.walls", d.solver.walls, {"auto", "reflect", "particles"},
                              "Domain walls: reflect (the seed's) or particles (Akinci et al. "
                              "2012 boundary particles); auto: reflect for seed, particles for "
                              "the others.");
    s.solver.artificial_viscosity =
        r.number("solver.artificial_viscosity", d.solver.artificial_viscosity, "",
                 "Alpha of Monaghan's artificial viscosity (wcsph).", Bound::non_negative);
    s.solver.tolerance =
        r.number("solver.tolerance", d.solver.tolerance, "%",
                 "dfsph: mean density error the density solve stops at.", Bound::positive);
    s.solver.divergence_tolerance = r.number(
        "solver.divergence_tolerance", d.solver.divergence_tolerance, "%",
        "dfsph: mean density change per step the divergence solve stops at.", Bound::positive);
    s.solver.min_iterations = r.integer("solver.min_iterations", d.solver.min_iterations, 0, 100000,
                                        "dfsph: fewest iterations of each solve.");
    s.solver.max_iterations = r.integer("solver.max_iterations", d.solver.max_iterations, 1, 100000,
                                        "dfsph: most iterations of each solve.");
    s.solver.warm_start = r.boolean("solver.warm_start", d.solver.warm_start,
                                    "dfsph: start each pressure solve from the last step's "
                                    "(2-3x fewer iterations; less accurate pressure in deep "
                                    "tanks).");
    s.solver.neighbour_search = r.choice("solver.neighbour_search", d.solver.neighbour_search,
                                         neighbour_search_names(), "Neighbour search.");
    s.solver.reorder_every =
        r.integer("solver.reorder_every", d.solver.reorder_every, 0, 1000000,
                  "Steps between spatial sorts of the particle arrays by grid cell (Morton "
                  "order), which keep neighbours near in memory; 0: never. Changes "
                  "round-off only.");
    s.solver.precision = r.choice(
        "solver.precision", d.solver.precision, {"auto", "single", "double"},
        "Arithmetic of wcsph's density and pressure passes: single (float, a grid cell at a "
        "time, no neighbour lists; 1.3-1.8x faster in 2D, even in 3D for more memory) or "
        "double (neighbour lists); auto: single in 2D where it can run (wcsph, a smooth "
        "kernel, the sorted grid, no XSPH or surface tension), else double.");

    s.watchdog.retries =
        r.integer("watchdog.retries", d.watchdog.retries, 0, 20,
                  "Times a step that fails the watchdog is retried, halved each time, "
                  "before the run stops with exit code 3.");
    s.watchdog.max_density_ratio =
        r.number("watchdog.max_density_ratio", d.watchdog.max_density_ratio, "",
                 "Density over rest density above which a step counts as failed (a collapse).",
                 Bound::positive);
    s.watchdog.max_displacement =
        r.number("watchdog.max_displacement", d.watchdog.max_displacement, "h",
                 "Support radii a particle may move in one step before the step counts as "
                 "failed (the CFL condition broken).",
                 Bound::positive);
    s.watchdog.max_speed = r.optional_number(
        "watchdog.max_speed", "m/s", "auto",
        "Speed above which a step counts as failed. Default: twice the sum of the sound "
        "speed, the speed of a fall over the whole domain, the fastest initial, "
        "emitter or paddle velocity, and the speed sqrt(2 e) that the compression energy e "
        "stored at the start (most at the densest particle) can release.",
        Bound::positive);

    // A scene that gives an `effects` object gets exactly the effects it lists.
    const auto gravity = r.optional_vector(
        "effects.gravity", dim, "m/s^2", format_vector(*d.effects.gravity, dim),
        "Gravity effect: a uniform acceleration. Absent from an `effects` object the scene "
        "gives (or null): no gravity.");
    s.effects.gravity = r.present("effects") ? gravity : d.effects.gravity;
    read_viscosity_effects(r, s);
    const double gamma = r.number(
        "effects.surface_tension.gamma", 1.0, "",
        "Surface tension effect (Akinci et al. 2013: cohesion and curvature), its "
        "coefficient gamma; a drop in zero gravity becomes round. Absent: no surface "
        "tension.",
        Bound::positive);
    if (r.present("effects.surface_tension"))
        s.effects.surface_tension = gamma;
    read_obstacles(r, dim, file, s.effects.obstacles);
    read_emitters(r, dim, s.effects.emitters);
    read_paddles(r, dim, s.effects.paddles);

    s.render.size = r.image_size("render.size", d.render.size, "Image width and height.");
    s.render.colour =
        r.choice("render.colour", d.render.colour, {"velocity", "density", "pressure"},
                 "Field the particles are coloured by.");
    s.render.colour_map = r.choice(
        "render.colour_map", d.render.colour_map, {"auto", "viridis", "turbo", "diverging"},
        "Colour map; auto: viridis for speed, diverging around rho0 for density, turbo "
        "for pressure.");
    if (const auto range = r.optional_vector("render.range", 2, "field unit", "from the scene",
                                             "Field values at the two ends of the colour map; by "
                                             "default speed 0..sqrt(2 g H), density rho0 +- 3%, "
                                             "pressure 0..rho0 g H (H: domain height).")) {
        if (!((*range)[0] < (*range)[1]))
            r.fail("render.range",
                   fmt::format("the low end must be below the high end, got [{}, {}]", (*range)[0],
                               (*range)[1]));
        s.render.range = std::array<double, 2>{(*range)[0], (*range)[1]};
    }
    s.render.spheres = r.choice("render.spheres", d.render.spheres, {"impostor", "mesh"},
                                "How spheres are drawn: ray-cast impostors (fast) or the seed's "
                                "instanced meshes.");
    s.render.cull_buried =
        r.boolean("render.cull_buried", d.render.cull_buried,
                  "3D: skip particles buried under two full layers of fluid (a camera outside "
                  "the fluid cannot see them); false draws every particle.");
    s.render.video_quality =
        r.integer("render.video_quality", d.render.video_quality, 0, 51,
                  "MP4 constant quality (x264 CRF): 0 lossless, 18-23 visually good, 51 worst.");
    s.render.video_preset =
        r.choice("render.video_preset", d.render.video_preset,
                 {"ultrafast", "superfast", "veryfast", "faster", "fast", "medium", "slow",
                  "slower", "veryslow"},
                 "MP4 encoder speed: faster presets make larger files at the same quality.");
    s.render.backend = r.choice("render.backend", d.render.backend, {"auto", "egl", "osmesa"},
                                "Headless GL context.");
    s.render.camera.position = r.optional_vector(
        "render.camera.position", 3, "m", "frames the domain", "Camera position (3D scenes).");
    s.render.camera.target = r.optional_vector("render.camera.target", 3, "m", "domain centre",
                                               "Point the camera looks at (3D scenes).");
    s.render.camera.fov = r.number("render.camera.fov", d.render.camera.fov, "degrees",
                                   "Vertical field of view (3D scenes).", Bound::positive);

    s.output.name = r.optional_text(
        "output.name", "the scene file's name",
        "Output folder under out/ when run has no --out: a relative path that stays inside "
        "out/ (not absolute, no \"..\").");
    if (s.output.name) {
        try {
            resolve_inside(output_root, *s.output.name, file, "output.name");
            json(*s.output.name).dump(); // run.json records it: UTF-8 or a type_error
        } catch (const InputError& e) {
            r.fail("output.name", e.problem);
        } catch (const json::type_error&) {
            r.fail("output.name", "is not valid UTF-8");
        }
    }

    r.reject_unknown_keys();
    if (docs)
        *docs = r.docs();

    // Checks that involve several fields.
    if (s.solver.dt_min > s.solver.dt_max)
        r.fail("solver.dt_min", fmt::format("must not exceed solver.dt_max ({} s), got {} s",
                                            s.solver.dt_max, s.solver.dt_min));
    if (s.solver.min_iterations > s.solver.max_iterations)
        r.fail("solver.min_iterations",
               fmt::format("must not exceed solver.max_iterations ({}), got {}",
                           s.solver.max_iterations, s.solver.min_iterations));
    if (s.solver.name == "dfsph" && s.solver.integrator != "symplectic_euler")
        r.fail("solver.integrator",
               "dfsph integrates with its own scheme (symplectic Euler between its two pressure "
               "solves); verlet is for the seed and wcsph solvers");
    if (s.solver.precision == "single") {
        const std::string obstacle = single_precision_obstacle(s, derive_kernel(s));
        if (!obstacle.empty())
            r.fail("solver.precision", "single: " + obstacle);
    }
    if (s.solver.name == "seed" && s.solver.walls == "particles")
        r.fail("solver.walls", "the seed solver's walls reflect; boundary particles are for "
                               "wcsph and dfsph");
    if (s.solver.name == "seed" && !s.effects.obstacles.empty())
        r.fail("effects.obstacles", "obstacles are made of boundary particles, which the seed "
                                    "solver (reflecting walls) does not have; use "
                                    "solver.name=wcsph or dfsph");
    if (s.solver.name == "seed" && !s.effects.paddles.empty())
        r.fail("effects.paddles", "paddles are made of boundary particles, which the seed "
                                  "solver (reflecting walls) does not have; use "
                                  "solver.name=wcsph or dfsph");
    // Past this the frame counter's conversion from floating point overflows,
    // and the per-frame records outgrow any disk.
    if (!(s.duration * s.fps <= max_frames))
        r.fail("duration",
               fmt::format("duration x fps gives {:.3g} frames; a clip has at most {:.0f}",
                           s.duration * s.fps, max_frames));
    for (int a = 0; a < dim; ++a) {
        if (!(s.domain.min[a] < s.domain.max[a]))
            r.fail("domain", fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                         "xyz"[a], s.domain.min[a], s.domain.max[a]));
        if (!std::isfinite(s.domain.max[a] - s.domain.min[a]))
            r.fail("domain", fmt::format("the size along axis {} ({} to {}) is beyond the range of "
                                         "a double",
                                         "xyz"[a], s.domain.min[a], s.domain.max[a]));
    }
    if (s.render.camera.fov >= 180)
        r.fail("render.camera.fov",
               fmt::format("must be below 180 degrees, got {}", s.render.camera.fov));
    if (s.fluid.blocks.empty())
        r.fail("fluid.blocks", "the scene has no fluid: give at least one block");
    const double ratio = s.fluid.smoothing_ratio.value_or(default_smoothing_ratio(dim));
    const double h = s.fluid.smoothing_length.value_or(ratio * s.fluid.spacing);
    // h in spacings sets the neighbours per particle and the reach of the
    // lattice sum in derive(); an overflowed h is infinitely many spacings.
    const double support = h / s.fluid.spacing;
    if (!(support >= 1 && support <= max_support))
        r.fail(s.fluid.smoothing_length ? "fluid.smoothing_length" : "fluid.smoothing_ratio",
               fmt::format("the support radius h = {} m is {:.3g} spacings of {} m; it must be 1 "
                           "to {:g} (below 1 a particle has no neighbour, above {:g} it has over "
                           "{:.0f} in {}D)",
                           h, support, s.fluid.spacing, max_support, max_support,
                           neighbours_within(dim, max_support), dim));
    // Cells are indexed by 64-bit integers: keep coordinates / h far from overflow.
    for (int a = 0; a < dim; ++a)
        if (std::max(std::abs(s.domain.min[a]), std::abs(s.domain.max[a])) / h > 1e15)
            r.fail("domain",
                   fmt::format("coordinates up to {} m are too far from the origin for "
                               "h = {} m",
                               std::max(std::abs(s.domain.min[a]), std::abs(s.domain.max[a])), h));
    // Counts in floating point, so that absurd requests are caught before any
    // cast or allocation; each axis on its own, so that 0 x infinity (NaN)
    // cannot slip past the limits below.
    // A box filled on the lattice (a block, an emitter's box): inside the
    // domain, at least one particle on every axis. Particles along each axis.
    auto lattice_box = [&](const std::string& p, const char* what, const Vec3& min,
                           const Vec3& max) {
        std::array<double, 3> along{1, 1, 1};
        for (int a = 0; a < dim; ++a) {
            if (!(min[a] < max[a]))
                r.fail(p, fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                      "xyz"[a], min[a], max[a]));
            const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
            if (min[a] < s.domain.min[a] - tolerance || max[a] > s.domain.max[a] + tolerance)
                r.fail(p, fmt::format("the {} [{}, {}] on axis {} is outside the domain [{}, {}]",
                                      what, min[a], max[a], "xyz"[a], s.domain.min[a],
                                      s.domain.max[a]));
            along[a] = std::floor((max[a] - min[a]) / s.fluid.spacing + 1e-9);
            if (!(along[a] >= 1))
                r.fail(p, fmt::format("the {} is thinner than one spacing ({} m) on axis {} and "
                                      "holds no particle",
                                      what, s.fluid.spacing, "xyz"[a]));
        }
        return along;
    };
    double total = 0;
    for (std::size_t i = 0; i < s.fluid.blocks.size(); ++i) {
        const auto& b = s.fluid.blocks[i];
        const auto along = lattice_box(fmt::format("fluid.blocks[{}]", i), "block", b.min, b.max);
        total += along[0] * along[1] * along[2];
    }
    // Emitters: every particle they will make by the end of the run counts
    // towards the limits.
    for (std::size_t i = 0; i < s.effects.emitters.size(); ++i) {
        const auto& e = s.effects.emitters[i];
        const auto along =
            lattice_box(fmt::format("effects.emitters[{}]", i), "emitter's box", e.min, e.max);
        double speed = 0, thickness = 0;
        for (int a = 0; a < dim; ++a)
            speed += e.velocity[a] * e.velocity[a];
        speed = std::sqrt(speed);
        for (int a = 0; a < dim; ++a)
            thickness += std::abs(e.velocity[a]) / speed * along[a] * s.fluid.spacing;
        const double running = std::max(0.0, std::min(e.end, s.duration) - e.start);
        total += along[0] * along[1] * along[2] * (std::floor(running * speed / thickness) + 1);
    }
    // Boundary particles (solver.walls = particles) fill layers around the
    // domain, and their lookup grid covers it.
    const bool wall_particles =
        s.solver.walls == "particles" || (s.solver.walls == "auto" && s.solver.name != "seed");
    double boundary = 0, grid_cells = 0;
    if (wall_particles) {
        const double layers = std::ceil(support);
        double outer = 1, inner = 1;
        grid_cells = 1;
        for (int a = 0; a < dim; ++a) {
            const double inside =
                std::floor((s.domain.max[a] - s.domain.min[a]) / s.fluid.spacing + 1e-9);
            outer *= inside + 2 * layers;
            inner *= inside;
            grid_cells *= std::floor((inside + 2 * layers) / support) + 1;
        }
        boundary = outer - inner;
    }
    // Obstacles' and paddles' shells; without wall particles their grid
    // covers at most the domain.
    for (std::size_t i = 0; i < s.effects.obstacles.size(); ++i)
        boundary += check_obstacle(r, s, i, std::ceil(support));
    for (std::size_t i = 0; i < s.effects.paddles.size(); ++i)
        boundary += check_paddle(r, s, i, std::ceil(support));
    if (!wall_particles && (!s.effects.obstacles.empty() || !s.effects.paddles.empty())) {
        grid_cells = 1;
        for (int a = 0; a < dim; ++a)
            grid_cells *=
                std::floor((s.domain.max[a] - s.domain.min[a]) / s.fluid.spacing / support) + 1;
    }
    const double fluid_bytes = total * bytes_per_particle(dim, support);
    const double wall_bytes = boundary * (2 * dim * 8 + 8 + 8 + 4) + grid_cells * 8;
    const double available = physical_memory_bytes();
    const double bytes = fluid_bytes + wall_bytes;
    if (!(total <= max_particles) || !(boundary <= max_particles) ||
        (available > 0 && !(bytes <= 0.8 * available))) {
        const std::string walls =
            boundary > 0 ? fmt::format(" and the walls {:.3g} boundary particles", boundary) : "";
        r.fail(fluid_bytes >= wall_bytes ? "fluid" : "domain",
               fmt::format("the blocks would hold {:.3g} particles{}, needing about {:.3g} GiB of "
                           "memory (this machine has {:.3g} GiB); use a larger fluid.spacing, "
                           "smaller blocks{}",
                           total, walls, bytes / (1 << 30), available / (1 << 30),
                           wall_particles ? " or a smaller domain" : ""));
    }
    // Extreme but valid values can still give derived ones a run cannot use.
    const Derived derived = derive(s);
    if (!(std::isfinite(derived.mass) && derived.mass > 0))
        r.fail("material.rest_density",
               fmt::format("the particle mass rho0 / (sum of W on the lattice) is {} kg for "
                           "rho0 = {} kg/m^3 and h = {} m; give values nearer to each other",
                           derived.mass, s.material.rest_density, h));
    if (!std::isfinite(derived.sound_speed))
        r.fail(
            "material.bulk_modulus",
            fmt::format("the speed of sound sqrt(K / rho0) overflows for K = {} Pa and rho0 = {} "
                        "kg/m^3",
                        s.material.bulk_modulus, s.material.rest_density));
    return s;
}

// Follows the keys down to where a parse stops, to name the field of an error
// inside a value. Builds nothing.
struct KeyTracker : nlohmann::json_sax<json> {
    std::vector<std::string> keys;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
        keys.emplace_back();
        return true;
    }
    bool key(string_t& name) override {
        keys.back() = name;
        return true;
    }
    bool end_object() override {
        keys.pop_back();
        return true;
    }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }
};

json parse_json_text(const std::string& text, const std::string& file) {
    try {
        // Without a callback: nlohmann's callback parser rescans a list at the
        // end of each of its objects, 11 s for a list of 20,000 under the
        // sanitizers (tests/fuzz/regressions/hand-many-blocks.json).
        return json::parse(text, nullptr, true, /*ignore_comments=*/true);
    } catch (const json::parse_error& e) {
        // Line and column from the byte offset nlohmann reports.
        const std::size_t offset = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
        const std::size_t line = 1 + std::count(text.begin(), text.begin() + offset, '\n');
        const std::size_t line_start = text.rfind('\n', offset == 0 ? 0 : offset - 1);
        const std::size_t column =
            line_start == std::string::npos ? offset + 1 : offset - line_start;
        std::string detail = e.what();
        if (auto colon = detail.find(": ", detail.find("column")); colon != std::string::npos)
            detail = detail.substr(colon + 2);
        throw InputError(
            file, "", fmt::format("invalid JSON at line {}, column {}: {}", line, column, detail));
    } catch (const json::exception& e) {
        // e.g. a number too large for a double: parsed again for its field.
        std::string detail = e.what();
        if (auto bracket = detail.find("] "); bracket != std::string::npos)
            detail = detail.substr(bracket + 2);
        KeyTracker tracker;
        json::sax_parse(text, &tracker, json::input_format_t::json, true,
                        /*ignore_comments=*/true);
        std::string field;
        for (const auto& k : tracker.keys)
            field += (field.empty() ? "" : ".") + k;
        throw InputError(file, field, detail);
    }
}

} // namespace

Scene parse_scene(const std::string& text, const std::string& file_label,
                  const std::vector<Override>& overrides) {
    json root = parse_json_text(text, file_label);
    if (!root.is_object())
        throw InputError(file_label, "", "a scene is a JSON object, got " + describe(root));
    std::set<std::string> overridden;
    for (const auto& o : overrides) {
        apply_override(root, o, file_label);
        overridden.insert(override_path(o.key));
    }
    return read_fields(root, file_label, std::move(overridden), nullptr);
}

Scene load_scene(const std::filesystem::path& file, const std::vector<Override>& overrides) {
    std::string text;
    try {
        text = read_input_file(file, scene_file_limit);
    } catch (const FileReadError& e) {
        throw InputError(file.string(), "", "cannot read the scene file: " + e.reason);
    }
    Scene s = parse_scene(text, file.string(), overrides);
    s.name = file.stem().string();
    return s;
}

Scene default_scene(const std::vector<Override>& overrides) {
    return parse_scene("{}", "built-in scene", overrides);
}

std::vector<KeyDoc> scene_keys() {
    // Vectors have D components: show the 2D and the 3D default.
    std::vector<KeyDoc> docs, docs_3d;
    read_fields(json::object(), "built-in scene", {}, &docs);
    read_fields(json{{"dimension", 3}}, "built-in scene", {}, &docs_3d);
    for (std::size_t i = 0; i < docs.size() && i < docs_3d.size(); ++i) {
        if (docs[i].type != docs_3d[i].type) {
            docs[i].type =
                docs[i].type.find("null") != std::string::npos ? "vector or null" : "vector";
            if (docs[i].default_value != docs_3d[i].default_value)
                docs[i].default_value += " (2D), " + docs_3d[i].default_value + " (3D)";
        }
    }
    return docs;
}

KernelKind kernel_kind(const std::string& name) {
    if (name == "cubic_spline")
        return KernelKind::cubic_spline;
    if (name == "wendland_c2")
        return KernelKind::wendland_c2;
    return KernelKind::seed;
}

TimeStepSettings time_step_settings(const Scene& s) {
    TimeStepSettings t;
    t.fixed = s.solver.dt.has_value();
    t.dt = s.solver.dt.value_or(0);
    t.cfl = s.solver.cfl;
    t.dt_min = s.solver.dt_min;
    t.dt_max = s.solver.dt_max;
    return t;
}

std::string single_precision_obstacle(const Scene& s, const std::string& kernel) {
    if (s.solver.name != "wcsph")
        return fmt::format("the single-precision passes are wcsph's; the {} solver computes in "
                           "double",
                           s.solver.name);
    if (kernel == "seed")
        return "the seed kernel's spiky gradient needs the double passes' rule for coincident "
               "particles; use solver.kernel cubic_spline or wendland_c2";
    if (s.solver.neighbour_search != "sorted_grid")
        return fmt::format("the single-precision passes run on the sorted grid's cells; "
                           "solver.neighbour_search {} lists neighbours for the double passes",
                           s.solver.neighbour_search);
    if (s.effects.viscosity && s.effects.viscosity->model != "morris")
        return fmt::format("effects.viscosity model {} reads neighbour lists, which the "
                           "single-precision passes do not build",
                           s.effects.viscosity->model);
    if (s.effects.xsph)
        return "effects.xsph reads neighbour lists, which the single-precision passes do not "
               "build";
    if (s.effects.surface_tension)
        return "effects.surface_tension reads neighbour lists, which the single-precision "
               "passes do not build";
    return {};
}

Derived derive(const Scene& s) {
    Derived d;
    const int dim = s.dimension;
    const double ratio = s.fluid.smoothing_ratio.value_or(default_smoothing_ratio(dim));
    d.h = s.fluid.smoothing_length.value_or(ratio * s.fluid.spacing);
    d.kernel = derive_kernel(s);
    // auto: single in 2D where it can run. In 3D the 27 cells around a
    // cell hold six candidates per neighbour, and single measured even with
    // double for 27% more memory (docs/solvers.md, "Single precision").
    d.precision = s.solver.precision != "auto" ? s.solver.precision
                  : dim == 2 && single_precision_obstacle(s, d.kernel).empty() ? "single"
                                                                                : "double";
    d.walls = s.solver.walls != "auto"  ? s.solver.walls
              : s.solver.name == "seed" ? "reflect"
                                        : "particles";
    if (s.fluid.mass) {
        d.mass = *s.fluid.mass;
    } else {
        // The density kernel's sum on the lattice: a lattice particle gets exactly rho0.
        const KernelKind kind = kernel_kind(d.kernel);
        const double sum =
            dim == 2 ? with_kernel<2>(
                           kind, d.h,
                           [&](const auto& W) { return lattice_kernel_sum<2>(W, s.fluid.spacing); })
                     : with_kernel<3>(kind, d.h, [&](const auto& W) {
                           return lattice_kernel_sum<3>(W, s.fluid.spacing);
                       });
        d.mass = s.material.rest_density / sum;
    }
    d.sound_speed = std::sqrt(s.material.bulk_modulus / s.material.rest_density);
    {
        // The fastest a motion of this scene can physically be: the sound
        // speed, a free fall over the whole box, and the fastest start (a
        // block's or an emitter's) or paddle; twice
        // that is garbage, however small the step (watchdog.max_speed).
        double g = 0, height = 0, v0 = 0;
        for (int a = 0; a < dim; ++a) {
            if (s.effects.gravity)
                g += (*s.effects.gravity)[a] * (*s.effects.gravity)[a];
            height = std::max(height, s.domain.max[a] - s.domain.min[a]);
        }
        auto fastest = [&](const Vec3& v) {
            double v2 = 0;
            for (int a = 0; a < dim; ++a)
                v2 += v[a] * v[a];
            v0 = std::max(v0, std::sqrt(v2));
        };
        for (const auto& b : s.fluid.blocks)
            fastest(b.velocity);
        for (const auto& e : s.effects.emitters)
            fastest(e.velocity);
        for (const auto& paddle : s.effects.paddles) {
            // The peak speed of its motion: |A| 2 pi / T or |V|.
            Vec3 peak = paddle.velocity;
            if (paddle.motion == "sine")
                for (int a = 0; a < dim; ++a)
                    peak[a] = paddle.amplitude[a] * 2 * M_PI / paddle.period;
            fastest(peak);
        }
        d.max_speed = s.watchdog.max_speed
                          ? *s.watchdog.max_speed
                          : 2 * (d.sound_speed + std::sqrt(2 * std::sqrt(g) * height) + v0);
    }
    d.fixed_dt = s.solver.dt.has_value();
    if (s.solver.dt) {
        d.dt = *s.solver.dt;
    } else {
        // The adaptive rule at rest under gravity: the first step's size.
        double g = 0;
        if (s.effects.gravity)
            for (int a = 0; a < dim; ++a)
                g += (*s.effects.gravity)[a] * (*s.effects.gravity)[a];
        d.dt = stable_time_step(
            time_step_settings(s),
            {d.h, s.fluid.spacing, d.sound_speed, s.material.rest_density,
             s.effects.viscosity ? s.effects.viscosity->mu : 0.0},
            {.carries_sound = s.solver.name != "dfsph"}, {0, std::sqrt(g)});
    }
    for (const auto& b : s.fluid.blocks) {
        std::size_t count = 1;
        for (int a = 0; a < dim; ++a)
            count *= lattice_count(b.min[a], b.max[a], s.fluid.spacing);
        d.particles += count;
    }
    return d;
}

std::filesystem::path output_folder(const Scene& s) {
    if (s.output.name)
        return resolve_inside(output_root, *s.output.name, s.file, "output.name");
    // The default, the scene file's name, is checked only here: "...json" is "..".
    try {
        return resolve_inside(output_root, s.name, s.file, "output.name");
    } catch (const InputError& e) {
        throw InputError(e.file, e.field,
                         e.problem + " (the default: the scene file's name); give output.name "
                                     "or --out");
    }
}

json to_json(const Scene& s) {
    const int dim = s.dimension;
    const Derived d = derive(s);
    auto vec = [dim](const Vec3& v) {
        return std::vector<double>(v.begin(), v.begin() + dim);
    };
    auto optional_vec = [](const std::optional<Vec3>& v) {
        return v ? json(std::vector<double>(v->begin(), v->end())) : json();
    };
    json blocks = json::array();
    for (const auto& b : s.fluid.blocks)
        blocks.push_back({{"min", vec(b.min)}, {"max", vec(b.max)}, {"velocity", vec(b.velocity)}});
    json effects = json::object();
    if (s.effects.gravity)
        effects["gravity"] = vec(*s.effects.gravity);
    // Both always written, 0 when off: read back, an absent key would let
    // material.viscosity or wcsph's solver.artificial_viscosity turn them on.
    effects["viscosity"] = s.effects.viscosity
                               ? json{{"model", s.effects.viscosity->model},
                                      {"mu", s.effects.viscosity->mu}}
                               : json{{"mu", 0.0}};
    effects["artificial_viscosity"] = {{"alpha", s.effects.artificial_viscosity.value_or(0.0)}};
    if (s.effects.xsph)
        effects["xsph"] = {{"epsilon", *s.effects.xsph}};
    if (s.effects.surface_tension)
        effects["surface_tension"] = {{"gamma", *s.effects.surface_tension}};
    if (!s.effects.obstacles.empty()) {
        json obstacles = json::array();
        for (const auto& o : s.effects.obstacles)
            obstacles.push_back(
                o.shape == ObstacleShape::box
                    ? json{{"box", {{"min", vec(o.min)}, {"max", vec(o.max)}}}}
                : o.shape == ObstacleShape::sphere
                    ? json{{"sphere", {{"centre", vec(o.centre)}, {"radius", o.radius}}}}
                    // The file as the scene names it, relative to the scene's folder.
                    : json{{"mesh",
                            {{"file", o.mesh_file},
                             {"scale", o.mesh_scale},
                             {"offset", vec(o.mesh_offset)}}}});
        effects["obstacles"] = obstacles;
    }
    if (!s.effects.emitters.empty()) {
        json emitters = json::array();
        for (const auto& e : s.effects.emitters)
            emitters.push_back({{"min", vec(e.min)},
                                {"max", vec(e.max)},
                                {"velocity", vec(e.velocity)},
                                {"start", e.start},
                                {"end", e.end}});
        for (std::size_t i = 0; i < s.effects.emitters.size(); ++i)
            if (const auto radius = s.effects.emitters[i].radius)
                emitters[i]["radius"] = *radius;
        effects["emitters"] = emitters;
    }
    if (!s.effects.paddles.empty()) {
        json paddles = json::array();
        for (const auto& o : s.effects.paddles) {
            json paddle = {{"min", vec(o.min)}, {"max", vec(o.max)}, {"motion", o.motion}};
            if (o.motion == "sine") {
                paddle["amplitude"] = vec(o.amplitude);
                paddle["period"] = o.period;
            } else {
                paddle["velocity"] = vec(o.velocity);
                paddle["end"] = o.end;
            }
            paddle["start"] = o.start;
            paddles.push_back(paddle);
        }
        effects["paddles"] = paddles;
    }
    return {
        {"dimension", dim},
        {"duration", s.duration},
        {"fps", s.fps},
        {"domain", {{"min", vec(s.domain.min)}, {"max", vec(s.domain.max)}}},
        {"fluid",
         {{"spacing", s.fluid.spacing},
          {"blocks", blocks},
          {"smoothing_ratio", d.h / s.fluid.spacing},
          {"smoothing_length", d.h},
          {"mass", d.mass}}},
        {"material",
         {{"rest_density", s.material.rest_density},
          {"bulk_modulus", s.material.bulk_modulus},
          {"viscosity", s.material.viscosity}}},
        {"solver",
         {{"name", s.solver.name},
          {"kernel", d.kernel},
          {"dt", s.solver.dt ? json(*s.solver.dt) : json()},
          {"cfl", s.solver.cfl},
          {"dt_min", s.solver.dt_min},
          {"dt_max", s.solver.dt_max},
          {"integrator", s.solver.integrator},
          {"walls", d.walls},
          {"artificial_viscosity", s.solver.artificial_viscosity},
          {"tolerance", s.solver.tolerance},
          {"divergence_tolerance", s.solver.divergence_tolerance},
          {"min_iterations", s.solver.min_iterations},
          {"max_iterations", s.solver.max_iterations},
          {"warm_start", s.solver.warm_start},
          {"neighbour_search", s.solver.neighbour_search},
          {"reorder_every", s.solver.reorder_every},
          {"precision", d.precision}}},
        {"watchdog",
         {{"retries", s.watchdog.retries},
          {"max_density_ratio", s.watchdog.max_density_ratio},
          {"max_displacement", s.watchdog.max_displacement},
          {"max_speed", s.watchdog.max_speed ? json(*s.watchdog.max_speed) : json()}}},
        {"effects", effects},
        {"render",
         {{"size", s.render.size},
          {"colour", s.render.colour},
          {"colour_map", s.render.colour_map},
          {"range", s.render.range ? json(*s.render.range) : json()},
          {"spheres", s.render.spheres},
          {"cull_buried", s.render.cull_buried},
          {"video_quality", s.render.video_quality},
          {"video_preset", s.render.video_preset},
          {"backend", s.render.backend},
          {"camera",
           {{"position", optional_vec(s.render.camera.position)},
            {"target", optional_vec(s.render.camera.target)},
            {"fov", s.render.camera.fov}}}}},
        {"output", {{"name", s.output.name.value_or(s.name)}}},
    };
}

} // namespace sph
