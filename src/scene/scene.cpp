#include "scene/scene.hpp"

#include "output/files.hpp"
#include "scene/field_reader.hpp"
#include "scene/input_error.hpp"
#include "scene/key_walk.hpp"
#include "scene/keys/effect_registry.hpp"
#include "scene/keys/scene_keys.hpp"
#include "scene/memory_limit.hpp"
#include "scene/scene_paths.hpp"
#include "sph/kernels.hpp"
#include "sph/lattice.hpp"
#include "sph/single_precision/single_passes.hpp"
#include "sph/solvers/solver.hpp"
#include "sph/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>

namespace sph {

namespace {

// Finds the first key given twice in one object, which JSON parsers
// (nlohmann's too) resolve silently by keeping the last: {"duration": 0.05,
// "duration": 0.1} would run 0.1 s. Builds nothing but the path to it.
struct DuplicateKeyFinder : nlohmann::json_sax<json> {
    struct Level {
        bool object = false;
        std::set<std::string> keys;
        std::string key;       // object: the key being read
        std::size_t items = 0; // array: elements seen so far
    };
    std::vector<Level> levels;
    std::string duplicate; // its path; empty when none

    std::string path_to(const std::string& last) const {
        std::string path;
        for (const Level& level : levels) {
            if (&level == &levels.back())
                break;
            path += level.object ? (path.empty() ? "" : ".") + level.key
                                 : fmt::format("[{}]", level.items - 1);
        }
        return path + (path.empty() ? "" : ".") + last;
    }
    bool value() {
        if (!levels.empty() && !levels.back().object)
            ++levels.back().items;
        return true;
    }
    bool null() override { return value(); }
    bool boolean(bool) override { return value(); }
    bool number_integer(number_integer_t) override { return value(); }
    bool number_unsigned(number_unsigned_t) override { return value(); }
    bool number_float(number_float_t, const string_t&) override { return value(); }
    bool string(string_t&) override { return value(); }
    bool binary(binary_t&) override { return value(); }
    bool start_object(std::size_t) override {
        value();
        levels.push_back({true, {}, {}, 0});
        return true;
    }
    bool key(string_t& name) override {
        if (!levels.back().keys.insert(name).second) {
            duplicate = path_to(name);
            return false;
        }
        levels.back().key = name;
        return true;
    }
    bool end_object() override {
        levels.pop_back();
        return true;
    }
    bool start_array(std::size_t) override {
        value();
        levels.push_back({false, {}, {}, 0});
        return true;
    }
    bool end_array() override {
        levels.pop_back();
        return true;
    }
    bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
        return false;
    }
};

// Refuses a key given twice in one object of `text` (valid JSON), naming it.
void reject_duplicate_keys(const std::string& text, const std::string& file,
                           const std::string& field_prefix = {}) {
    DuplicateKeyFinder finder;
    json::sax_parse(text, &finder, json::input_format_t::json, true, /*ignore_comments=*/true);
    if (!finder.duplicate.empty())
        throw InputError(
            file, field_prefix.empty() ? finder.duplicate : field_prefix + "." + finder.duplicate,
            "the key is given twice in the same object (JSON would keep only the "
            "last); give it once");
}

// An ASCII digit. ::isdigit of a char above 127 (a byte of UTF-8 in a key)
// is undefined behaviour.
bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

// Sets root[path] = value for `--set path=value`, creating objects on the way.
void apply_override(json& root, const Override& o, const std::string& file) {
    const std::string field = o.key + " (from --set)";
    if (o.key.empty())
        throw InputError(file, "--set", "expected KEY=VALUE, got an empty key");
    // JSON when it parses as JSON, else the text itself as a string.
    json value;
    try {
        value = json::parse(o.value);
        if (value.is_structured())
            reject_duplicate_keys(o.value, file, field);
    } catch (const InputError&) {
        throw;
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
            if (!std::all_of(segment.begin(), segment.end(), is_digit))
                throw InputError(file, field,
                                 fmt::format("'{}' is a list; index it with a number",
                                             o.key.substr(0, begin - 1)));
            // Compared as text first: 99999999999999999999 overflows any integer.
            const std::string list = o.key.substr(0, begin - 1);
            const std::string size = std::to_string(node->size());
            if (segment.size() > size.size() || (segment.size() == size.size() && segment > size))
                throw InputError(file, field,
                                 fmt::format("index {} is past the end of '{}', a list of {}",
                                             segment.substr(0, 24), list, node->size()));
            const std::size_t index = std::stoul(segment);
            // A new element past a list's end is given whole; a key of it
            // alone would add an element of defaults unseen.
            if (index == node->size() && !last && node->size() > 0)
                throw InputError(file, field,
                                 fmt::format("'{}' has {} element{}, indices 0 to {}; to add one, "
                                             "give it whole: --set {}.{}={{...}}",
                                             list, node->size(), node->size() == 1 ? "" : "s",
                                             node->size() - 1, list, node->size()));
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
                if (!next.empty() && std::all_of(next.begin(), next.end(), is_digit))
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
KernelKind derive_kernel(const Scene& s) {
    return s.solver.kernel.value_or(solver_capabilities(s.solver.name).default_kernel);
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

// fluid.blocks: with no list in the scene the default block is read (and
// documented); a list replaces it, an empty one is refused later.
void read_blocks(FieldReader& r, Scene& s) {
    const Scene d;
    const std::size_t count = r.list("fluid.blocks", "one block, the dam-break column",
                                     "Boxes filled with fluid particles on the lattice.");
    if (r.present("fluid.blocks"))
        s.fluid.blocks.assign(count, FluidBlock{});
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const FluidBlock b = read_keys(r, fmt::format("fluid.blocks[{}]", i), block_keys(),
                                       d.fluid.blocks[0], s.dimension);
        if (i < s.fluid.blocks.size())
            s.fluid.blocks[i] = b;
    }
}

// An effect the `effects` object names is on, with the keys it gives and
// `fallback` for the others; an effect it does not name is off.
template <class S>
std::optional<S> read_effect(FieldReader& r, const std::string& name, const KeyTable<S>& keys,
                             const S& fallback, int dimension) {
    const std::string path = "effects." + name;
    S settings = read_keys(r, path, keys, fallback, dimension);
    return r.present(path) ? std::optional(settings) : std::nullopt;
}

// The effects with their keys declared in sph/effects/. A scene that gives an
// `effects` object gets exactly the effects it lists, but for those that the
// rest of the scene implies (Settings::implied: viscosity from
// material.viscosity, wcsph's solver.artificial_viscosity) unless their key
// says otherwise; an effect whose values turn it off (a coefficient of 0) is
// not in the step.
void read_effects(FieldReader& r, Scene& s) {
    const bool listed = r.present("effects");
    const EffectScene scene{s.solver, solver_capabilities(s.solver.name), s.material.viscosity};
    for_each_registered_effect([&](const auto& entry) {
        using S = typename std::decay_t<decltype(entry)>::Settings;
        auto& effect = s.effects.*entry.field;
        const S fallback = effect_defaults<S>(scene);
        const auto given = read_effect(r, S::key, entry.keys(), fallback, s.dimension);
        if (given || listed)
            effect = given;
        if (effect && !effect_on(*effect))
            effect.reset();
        else if (!r.present(std::string("effects.") + S::key) && effect_implied<S>(scene) &&
                 effect_on(fallback))
            effect = fallback;
    });
    for_each_effect(s.effects, [&](const auto& effect) {
        if (const auto problem = effect_problem(effect))
            r.fail(key_path(std::string("effects.") + effect.key, problem->path), problem->problem);
    });
}

void check_render_range(const FieldReader& r, const Scene& s) {
    if (const auto& range = s.render.range; range && !((*range)[0] < (*range)[1]))
        r.fail("render.range", fmt::format("the low end must be below the high end, got [{}, {}]",
                                           (*range)[0], (*range)[1]));
}

// render.surface's lengths in their documented ranges (the voxel sets the
// level set's memory, ~ 1 / voxel^3), and a 3D surface only where this build
// has OpenVDB (SPHCLIP_HAVE_OPENVDB, CMake option SPHCLIP_OPENVDB).
void check_render_surface(const FieldReader& r, const Scene& s) {
    const Scene::Render::Surface& f = s.render.surface;
    if (!(f.voxel >= 0.1 && f.voxel <= 2))
        r.fail("render.surface.voxel",
               fmt::format("must be 0.1 to 2 particle spacings, got {}", f.voxel));
    if (!(f.radius >= 0.5 && f.radius <= 4))
        r.fail("render.surface.radius",
               fmt::format("must be 0.5 to 4 particle spacings, got {}", f.radius));
    if (s.render.style != FluidStyle::surface || s.dimension != 3)
        return;
    // OpenVDB's rasteriser drops spheres under 1.5 voxels: nothing would show.
    if (f.radius < 1.5 * f.voxel)
        r.fail("render.surface.radius",
               fmt::format("must be at least 1.5 voxels (render.surface.voxel = {}), got {}",
                           f.voxel, f.radius));
#ifndef SPHCLIP_HAVE_OPENVDB
    r.fail("render.style", "surface in 3D needs OpenVDB, and this sphclip was built without it "
                           "(install libopenvdb-dev and configure with -DSPHCLIP_OPENVDB=ON); "
                           "2D scenes and render.style = spheres work without it");
#endif
}

// output.name stays inside out/, and run.json records it: UTF-8 or a type_error.
void check_output_name(const FieldReader& r, const Scene& s) {
    if (!s.output.name)
        return;
    try {
        resolve_inside(output_root, *s.output.name, s.file, "output.name");
        json(*s.output.name).dump();
    } catch (const InputError& e) {
        r.fail("output.name", e.problem);
    } catch (const json::type_error&) {
        r.fail("output.name", "is not valid UTF-8");
    }
}

// The solver's keys against each other and against what the solver can do.
void check_solver(const FieldReader& r, const Scene& s) {
    const SolverCapabilities& solver = solver_capabilities(s.solver.name);
    // A threshold below 1 would cut the ranges again at every step.
    if (!(s.solver.rebalance_above >= 1 && s.solver.rebalance_above <= 1000))
        r.fail("solver.rebalance_above",
               fmt::format("must be between 1 and 1000 (the fullest rank's particles over the "
                           "mean), got {}",
                           s.solver.rebalance_above));
    if (s.solver.dt_min > s.solver.dt_max)
        r.fail("solver.dt_min", fmt::format("must not exceed solver.dt_max ({} s), got {} s",
                                            s.solver.dt_max, s.solver.dt_min));
    // At 1 a pressure step would never die out.
    if (!(s.solver.momentum < 1))
        r.fail("solver.momentum",
               fmt::format("must be below 1 (0: no heavy-ball term), got {}", s.solver.momentum));
    if (s.solver.min_iterations > s.solver.max_iterations)
        r.fail("solver.min_iterations",
               fmt::format("must not exceed solver.max_iterations ({}), got {}",
                           s.solver.max_iterations, s.solver.min_iterations));
    if (!solver.supports_verlet && s.solver.integrator == Integrator::verlet)
        r.fail("solver.integrator",
               "dfsph integrates with its own scheme (symplectic Euler between its two pressure "
               "solves); verlet is for the seed and wcsph solvers");
    if (s.solver.wall_pressure == WallPressure::extrapolated && s.solver.name != SolverKind::wcsph)
        r.fail("solver.wall_pressure",
               fmt::format("extrapolated is wcsph's (the {} solver's walls take the fluid "
                           "particle's own pressure); use mirror or hydrostatic",
                           solver.name));
    if (s.solver.density_diffusion > 0 && s.solver.name == SolverKind::wcsph &&
        s.solver.integrator == Integrator::verlet)
        r.fail("solver.density_diffusion",
               "wcsph's carried density advances with symplectic Euler (after the kick, as the "
               "positions); use solver.integrator symplectic_euler, or 0 to sum the density");
    if (s.solver.precision == Precision::single) {
        const std::string obstacle = single_precision_obstacle(s, derive_kernel(s));
        if (!obstacle.empty())
            r.fail("solver.precision", "single: " + obstacle);
    }
    if (s.solver.pair_terms == PairTerms::once &&
        (s.dimension != 3 || s.solver.precision != Precision::single))
        r.fail("solver.pair_terms",
               "once is for 3D wcsph in single precision (solver.precision single); 2D and "
               "the double passes take each pair from both sides");
    if (!solver.wall_particles && s.solver.walls == WallModel::particles)
        r.fail("solver.walls", "the seed solver's walls reflect; boundary particles are for "
                               "wcsph and dfsph");
    if (!solver.wall_particles && !s.effects.obstacles.empty())
        r.fail("effects.obstacles", "obstacles are made of boundary particles, which the seed "
                                    "solver (reflecting walls) does not have; use "
                                    "solver.name=wcsph or dfsph");
    if (!solver.wall_particles && !s.effects.paddles.empty())
        r.fail("effects.paddles", "paddles are made of boundary particles, which the seed "
                                  "solver (reflecting walls) does not have; use "
                                  "solver.name=wcsph or dfsph");
}

// The clip's length, the domain's box, the camera and the presence of fluid.
void check_clip(const FieldReader& r, const Scene& s) {
    // Past this the frame counter's conversion from floating point overflows,
    // and the per-frame records outgrow any disk.
    if (!(s.duration * s.fps <= max_frames))
        r.fail("duration",
               fmt::format("duration x fps gives {:.3g} frames; a clip has at most {:.0f}",
                           s.duration * s.fps, max_frames));
    for (int a = 0; a < s.dimension; ++a) {
        if (!(s.domain.min[a] < s.domain.max[a]))
            r.fail("domain", fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                         "xyz"[a], s.domain.min[a], s.domain.max[a]));
        if (!std::isfinite(s.domain.max[a] - s.domain.min[a]))
            r.fail("domain", fmt::format("the size along axis {} ({} to {}) is beyond the range of "
                                         "a double",
                                         "xyz"[a], s.domain.min[a], s.domain.max[a]));
    }
    if (s.fluid.blocks.empty())
        r.fail("fluid.blocks", "the scene has no fluid: give at least one block");
}

// The support radius h, checked in spacings and against the domain's coordinates.
double check_support(const FieldReader& r, const Scene& s) {
    const int dim = s.dimension;
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
    return h;
}

// A box filled on the lattice (a block, an emitter's box): inside the domain,
// at least one particle on every axis. Returns the particles along each axis,
// in floating point, so that absurd requests are caught before any cast or
// allocation; each axis on its own, so that 0 x infinity (NaN) cannot slip
// past the limits.
std::array<double, 3> check_lattice_box(const FieldReader& r, const Scene& s, const std::string& p,
                                        const char* what, const Vec3& min, const Vec3& max) {
    std::array<double, 3> along{1, 1, 1};
    for (int a = 0; a < s.dimension; ++a) {
        if (!(min[a] < max[a]))
            r.fail(p, fmt::format("min must be below max on every axis (axis {}: {} >= {})",
                                  "xyz"[a], min[a], max[a]));
        const double tolerance = 1e-9 * (s.domain.max[a] - s.domain.min[a]);
        if (min[a] < s.domain.min[a] - tolerance || max[a] > s.domain.max[a] + tolerance)
            r.fail(p, fmt::format("the {} [{}, {}] on axis {} is outside the domain [{}, {}]", what,
                                  min[a], max[a], "xyz"[a], s.domain.min[a], s.domain.max[a]));
        along[a] = std::floor((max[a] - min[a]) / s.fluid.spacing + 1e-9);
        if (!(along[a] >= 1))
            r.fail(p, fmt::format("the {} is thinner than one spacing ({} m) on axis {} and "
                                  "holds no particle",
                                  what, s.fluid.spacing, "xyz"[a]));
    }
    return along;
}

// Fluid particles: the blocks', and every particle the emitters will make by
// the end of the run.
double count_fluid_particles(const FieldReader& r, const Scene& s) {
    double total = 0;
    for (std::size_t i = 0; i < s.fluid.blocks.size(); ++i) {
        const auto& b = s.fluid.blocks[i];
        const auto along =
            check_lattice_box(r, s, fmt::format("fluid.blocks[{}]", i), "block", b.min, b.max);
        total += along[0] * along[1] * along[2];
    }
    for (std::size_t i = 0; i < s.effects.emitters.size(); ++i) {
        const auto& e = s.effects.emitters[i];
        const auto along = check_lattice_box(r, s, fmt::format("effects.emitters[{}]", i),
                                             "emitter's box", e.min, e.max);
        double speed = 0, thickness = 0;
        for (int a = 0; a < s.dimension; ++a)
            speed += e.velocity[a] * e.velocity[a];
        speed = std::sqrt(speed);
        for (int a = 0; a < s.dimension; ++a)
            thickness += std::abs(e.velocity[a]) / speed * along[a] * s.fluid.spacing;
        const double running = std::max(0.0, std::min(e.end, s.duration) - e.start);
        total += along[0] * along[1] * along[2] * (std::floor(running * speed / thickness) + 1);
    }
    return total;
}

// The particles and the memory the scene asks for, against the limits of
// the indices and of this machine.
void check_size(const FieldReader& r, const Scene& s, double h) {
    const int dim = s.dimension;
    const double support = h / s.fluid.spacing;
    const double total = count_fluid_particles(r, s);
    // Boundary particles (solver.walls = particles) fill layers around the
    // domain, and their lookup grid covers it.
    const bool wall_particles =
        s.solver.walls == WallModel::particles ||
        (!s.solver.walls && solver_capabilities(s.solver.name).wall_particles);
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
    // The arrays counted above are not all a run holds (the watchdog's saved
    // state, solver scratch, the sort, allocator slack): measured at the peak
    // of the address space, --threads 1, 2026-12, a 2D run of 1M particles took
    // 464 bytes a particle and a 3D one of 512k 697, 2.2 and 2.0 times the
    // count; 2.5 keeps a margin, so that a scene accepted does not run out.
    constexpr double measured_over_counted = 2.5;
    const double fluid_bytes = measured_over_counted * total * bytes_per_particle(dim, support);
    const double wall_bytes = boundary * (2 * dim * 8 + 8 + 8 + 4) + grid_cells * 8;
    // RAM, ulimit -v and the cgroup's limit: the tightest (scene/memory_limit.hpp).
    const MemoryLimit memory = memory_limit();
    const double available = memory.bytes;
    const double bytes = fluid_bytes + wall_bytes;
    if (!(total <= max_particles) || !(boundary <= max_particles) ||
        (available > 0 && !(bytes <= 0.8 * available))) {
        const std::string walls =
            boundary > 0 ? fmt::format(" and the walls {:.3g} boundary particles", boundary) : "";
        r.fail(fluid_bytes >= wall_bytes ? "fluid" : "domain",
               fmt::format("the blocks would hold {:.3g} particles{}, needing about {:.3g} GiB of "
                           "memory (at most 80% of what it may use: {}); use a larger "
                           "fluid.spacing, smaller blocks{}",
                           total, walls, bytes / (1 << 30),
                           memory.what.empty() ? "unknown" : memory.what,
                           wall_particles ? " or a smaller domain" : ""));
    }
}

// Extreme but valid values can still give derived ones a run cannot use.
void check_derived(const FieldReader& r, const Scene& s, double h) {
    const Derived derived = derive(s);
    const int dim = s.dimension;
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
    // Every derived quantity a step or a stats row multiplies must be far
    // from the ends of the precision the run computes in (single in 2D by
    // default): 1e6 of room each way, so that their products in a step stay
    // finite and nonzero, and no frame (frame 0 is written before any step)
    // holds inf, NaN or a value flushed to 0.
    const bool single = derived.precision == Precision::single;
    const double largest = (single ? 3.4028234663852886e38 : 1.7976931348623157e308) * 1e-6;
    const double smallest = (single ? 1.1754943508222875e-38 : 2.2250738585072014e-308) * 1e6;
    const auto within = [&](double value, bool zero_allowed) {
        const double size = std::abs(value);
        return std::isfinite(value) && size <= largest &&
               (size >= smallest || (zero_allowed && size == 0));
    };
    const auto refuse = [&](const std::string& key, const std::string& quantity, double value) {
        r.fail(key, fmt::format("{} is {:.3g}, beyond what the run can compute with (magnitudes "
                                "{:.3g} to {:.3g} in {} precision); give values nearer to each "
                                "other",
                                quantity, value, smallest, largest, single ? "single" : "double"));
    };
    const double volume = std::pow(s.fluid.spacing, dim);
    const double density = derived.mass / volume; // about the density a lattice particle gets
    const std::string mass_key = s.fluid.mass ? "fluid.mass" : "material.rest_density";
    if (!within(derived.mass, false))
        refuse(mass_key, "the particle mass", derived.mass);
    if (!within(density, false))
        refuse(mass_key, "the density a particle gets, its mass / fluid.spacing^d,", density);
    if (!within(s.material.rest_density, false))
        refuse("material.rest_density", "material.rest_density", s.material.rest_density);
    if (!within(derived.sound_speed, false) ||
        !within(derived.sound_speed * derived.sound_speed, false))
        refuse("material.bulk_modulus", "the speed of sound sqrt(K / rho0)", derived.sound_speed);
    // The pressure of a fluid compressed tenfold, Tait's law at gamma = 7.
    if (!within(s.material.bulk_modulus * 1e7, false))
        refuse("material.bulk_modulus",
               "the pressure scale K (rho / rho0)^7 at tenfold "
               "compression",
               s.material.bulk_modulus * 1e7);
    if (!within(derived.dt, false))
        refuse(s.solver.dt ? "solver.dt" : "material.bulk_modulus", "the time step", derived.dt);
    // A fixed step far below the clip's length never finishes: a billion
    // steps is days even at the fastest step this program takes.
    constexpr double max_steps = 1e9;
    if (s.solver.dt && s.duration / *s.solver.dt > max_steps)
        r.fail("solver.dt",
               fmt::format("{:.3g} s over a duration of {:.3g} s is {:.3g} steps, more "
                           "than the {:.0e} a run may take; give a larger step or "
                           "leave it out (adaptive)",
                           *s.solver.dt, s.duration, s.duration / *s.solver.dt, max_steps));
    for (std::size_t i = 0; i < s.fluid.blocks.size(); ++i) {
        double v2 = 0;
        for (int a = 0; a < dim; ++a)
            v2 += s.fluid.blocks[i].velocity[a] * s.fluid.blocks[i].velocity[a];
        const double energy =
            0.5 * derived.mass * v2 * double(std::max<std::size_t>(derived.particles, 1));
        if (!within(v2, true) || !within(energy, true))
            refuse(fmt::format("fluid.blocks[{}].velocity", i), "the kinetic energy of the blocks",
                   energy);
    }
    if (s.effects.gravity) {
        double g2 = 0;
        for (int a = 0; a < dim; ++a)
            g2 += s.effects.gravity->acceleration[a] * s.effects.gravity->acceleration[a];
        if (!within(g2, true) || !within(g2 * derived.dt * derived.dt, true))
            refuse("effects.gravity", "the square of the gravity's acceleration", g2);
    }
    if (!within(derived.max_speed * derived.max_speed, true))
        refuse(s.watchdog.max_speed ? "watchdog.max_speed" : "material.bulk_modulus",
               "the square of the largest speed the watchdog allows", derived.max_speed);
}

// Reads every key (the tables in scene/keys/, sph/solvers/ and sph/effects/, in
// the order `sphclip keys` lists them), refuses unknown ones, then checks the
// fields against each other.
Scene read_fields(const json& root, const std::string& file, std::set<std::string> overridden,
                  std::vector<KeyDoc>* docs) {
    FieldReader r(root, file, std::move(overridden));
    const Scene d; // defaults
    Scene s;
    s.file = file;
    read_keys(r, "", top_level_keys(), d, s, 2); // no vectors: the dimension comes first
    const int dim = s.dimension;
    read_keys(r, "domain", domain_keys(), d.domain, s.domain, dim);
    read_keys(r, "fluid", fluid_keys(), d.fluid, s.fluid, dim);
    read_blocks(r, s);
    read_keys(r, "material", material_keys(), d.material, s.material, dim);
    read_keys(r, "solver", solver_keys(), d.solver, s.solver, dim);
    read_keys(r, "watchdog", watchdog_keys(), d.watchdog, s.watchdog, dim);
    read_effects(r, s);
    s.effects.obstacles = read_obstacles(r, dim, file);
    s.effects.emitters = read_list(r, emitter_keys(), dim);
    s.effects.paddles = read_list(r, paddle_keys(), dim);
    read_keys(r, "render", render_keys(), d.render, s.render, dim);
    check_render_range(r, s);
    read_camera(r, s);
    read_keys(r, "render.surface", surface_keys(), d.render.surface, s.render.surface, dim);
    check_render_surface(r, s);
    read_keys(r, "output", output_keys(), d.output, s.output, dim);
    check_output_name(r, s);
    r.reject_unknown_keys();
    if (docs)
        *docs = r.docs();

    check_solver(r, s);
    check_clip(r, s);
    const double h = check_support(r, s);
    check_size(r, s, h);
    check_derived(r, s, h);
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
        json root = json::parse(text, nullptr, true, /*ignore_comments=*/true);
        reject_duplicate_keys(text, file);
        return root;
    } catch (const InputError&) {
        throw;
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

TimeStepSettings time_step_settings(const Scene& s) {
    TimeStepSettings t;
    t.fixed = s.solver.dt.has_value();
    t.dt = s.solver.dt.value_or(0);
    t.cfl = s.solver.cfl;
    t.dt_min = s.solver.dt_min;
    t.dt_max = s.solver.dt_max;
    return t;
}

std::string single_precision_obstacle(const Scene& s, KernelKind kernel) {
    if (!solver_capabilities(s.solver.name).single_precision)
        return fmt::format("the single-precision passes are wcsph's; the {} solver computes in "
                           "double",
                           solver_capabilities(s.solver.name).name);
    if (s.solver.density_diffusion > 0)
        return "solver.density_diffusion carries wcsph's density in the double passes";
    if (s.solver.wall_pressure == WallPressure::extrapolated)
        return "solver.wall_pressure extrapolated is computed in the double passes";
    if (!smooth_at_origin(kernel))
        return "the seed kernel's spiky gradient needs the double passes' rule for coincident "
               "particles; use solver.kernel cubic_spline or wendland_c2";
    if (s.solver.neighbour_search != NeighbourSearchKind::sorted_grid)
        return fmt::format("the single-precision passes run on the sorted grid's cells; "
                           "solver.neighbour_search {} lists neighbours for the double passes",
                           neighbour_search_names()[static_cast<int>(s.solver.neighbour_search)]);
    std::string problem;
    for_each_effect(s.effects, [&](const auto& effect) {
        if (problem.empty() && effect.capabilities().reads_neighbour_lists)
            problem = fmt::format("{} reads neighbour lists, which the single-precision passes "
                                  "do not build",
                                  effect.label());
    });
    if (!problem.empty())
        return problem;
    return {};
}

Derived derive(const Scene& s) {
    Derived d;
    const int dim = s.dimension;
    const double ratio = s.fluid.smoothing_ratio.value_or(default_smoothing_ratio(dim));
    d.h = s.fluid.smoothing_length.value_or(ratio * s.fluid.spacing);
    d.kernel = derive_kernel(s);
    d.walls = s.solver.walls.value_or(solver_capabilities(s.solver.name).wall_particles
                                          ? WallModel::particles
                                          : WallModel::reflect);
    if (s.fluid.mass) {
        d.mass = *s.fluid.mass;
    } else {
        // The density kernel's sum on the lattice: a lattice particle gets exactly rho0.
        const KernelKind kind = d.kernel;
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
                g += s.effects.gravity->acceleration[a] * s.effects.gravity->acceleration[a];
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
            if (paddle.motion == PaddleMotion::sine)
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
                g += s.effects.gravity->acceleration[a] * s.effects.gravity->acceleration[a];
        d.dt = stable_time_step(time_step_settings(s),
                                {d.h, s.fluid.spacing, d.sound_speed, s.material.rest_density,
                                 diffusion_viscosity(s.effects)},
                                {.carries_sound = solver_capabilities(s.solver.name).carries_sound},
                                {0, std::sqrt(g)});
    }
    for (const auto& b : s.fluid.blocks) {
        std::size_t count = 1;
        for (int a = 0; a < dim; ++a)
            count *= lattice_count(b.min[a], b.max[a], s.fluid.spacing);
        d.particles += count;
    }
    // solver.precision auto: single where it can run and the processor runs
    // its passes 8 floats wide or more (single_passes_pay); in 3D from this
    // many fluid particles at the start (counted as pair_terms' below).
    // Measured on an Intel Xeon, 2 threads (docs/benchmarks.md, "Single
    // precision, the 3D default"): 1.4x double in the flow of a 3D dam break
    // at 97k particles, with AVX-512 and with AVX2; from rest 1.13-1.26x at
    // 3,600 to 11,700 particles, 1.0-1.2x at 33k and 94k, at par at 2,000 to
    // 2,700 and 0.88-0.92x at 1,365. For about 27% more memory.
    constexpr std::size_t single_3d_from = 2000;
    d.precision = s.solver.precision ? *s.solver.precision
                  : single_precision_obstacle(s, d.kernel).empty() && single_passes_pay() &&
                          (dim == 2 || d.particles >= single_3d_from)
                      ? Precision::single
                      : Precision::double_precision;
    // solver.pair_terms auto: once for 3D single precision from this many
    // fluid particles at the start, a count every MPI rank and thread count
    // sees alike, so the bits change with neither. Measured on 2 cores
    // (docs/benchmarks.md, the pairs-once entry): 1.07-1.27x both sides at
    // 11,700 to 97,000 particles, 0.65x at 858-1,365, where too few tiles of
    // 4^3 cells fill each colour for two threads to share.
    constexpr std::size_t pairs_once_from = 10000;
    d.pair_terms = s.solver.pair_terms.value_or(dim == 3 && d.precision == Precision::single &&
                                                        d.particles >= pairs_once_from
                                                    ? PairTerms::once
                                                    : PairTerms::both_sides);
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
    // The scene as resolved: derived values in place of "auto" and of absent keys.
    Scene r = s;
    r.fluid.smoothing_ratio = d.h / s.fluid.spacing;
    r.fluid.smoothing_length = d.h;
    r.fluid.mass = d.mass;
    r.solver.kernel = d.kernel;
    r.solver.walls = d.walls;
    r.solver.precision = d.precision;
    r.solver.pair_terms = d.pair_terms;
    r.output.name = s.output.name.value_or(s.name);

    json effects = json::object();
    for_each_registered_effect([&](const auto& entry) {
        using S = typename std::decay_t<decltype(entry)>::Settings;
        if (const auto& settings = r.effects.*entry.field)
            effects[S::key] = write_keys(entry.keys(), *settings, dim);
        else if constexpr (requires { S::off_key; })
            effects[S::key] = {{S::off_key, 0.0}}; // read back, nothing implies it
    });
    if (!r.effects.obstacles.empty())
        effects["obstacles"] = write_list(obstacle_keys(), r.effects.obstacles, dim);
    if (!r.effects.emitters.empty())
        effects["emitters"] = write_list(emitter_keys(), r.effects.emitters, dim);
    if (!r.effects.paddles.empty())
        effects["paddles"] = write_list(paddle_keys(), r.effects.paddles, dim);

    json out = write_keys(top_level_keys(), r, dim);
    out["domain"] = write_keys(domain_keys(), r.domain, dim);
    out["fluid"] = write_keys(fluid_keys(), r.fluid, dim);
    out["fluid"]["blocks"] = json::array();
    for (const auto& b : r.fluid.blocks)
        out["fluid"]["blocks"].push_back(write_keys(block_keys(), b, dim));
    out["material"] = write_keys(material_keys(), r.material, dim);
    out["solver"] = write_keys(solver_keys(), r.solver, dim);
    out["watchdog"] = write_keys(watchdog_keys(), r.watchdog, dim);
    out["effects"] = effects;
    out["render"] = write_keys(render_keys(), r.render, dim);
    out["render"]["camera"] = write_camera(r.render.camera, dim);
    out["render"]["surface"] = write_keys(surface_keys(), r.render.surface, dim);
    out["output"] = write_keys(output_keys(), r.output, dim);
    return out;
}

} // namespace sph
