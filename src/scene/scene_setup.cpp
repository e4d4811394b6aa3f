#include "scene/scene_setup.hpp"

#include "scene/input_error.hpp"
#include "scene/keys/effect_registry.hpp"
#include "sph/effects/artificial_viscosity.hpp"
#include "sph/effects/gravity.hpp"
#include "sph/effects/laminar_viscosity.hpp"
#include "sph/effects/seed_viscosity.hpp"
#include "sph/effects/surface_tension.hpp"
#include "sph/effects/xsph.hpp"
#include "sph/lattice.hpp"
#include "sph/sources/emitter.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <limits>

namespace sph {

namespace {
template <int D>
Vec<D> to_vec(const Vec3& v) {
    Vec<D> out;
    for (int a = 0; a < D; ++a)
        out[a] = v[a];
    return out;
}

template <int D>
std::vector<Obstacle<D>> make_obstacles(const Scene& scene) {
    std::vector<Obstacle<D>> obstacles;
    for (const auto& o : scene.effects.obstacles)
        obstacles.push_back(
            {o.shape, {to_vec<D>(o.min), to_vec<D>(o.max)}, to_vec<D>(o.centre), o.radius, o.mesh});
    return obstacles;
}
} // namespace

template <int D>
std::vector<Paddle<D>> make_paddles(const Scene& scene) {
    std::vector<Paddle<D>> paddles;
    for (const auto& o : scene.effects.paddles) {
        Paddle<D> p;
        p.box = {to_vec<D>(o.min), to_vec<D>(o.max)};
        p.motion = o.motion;
        p.amplitude = to_vec<D>(o.amplitude);
        p.period = o.period;
        p.velocity = to_vec<D>(o.velocity);
        p.start = o.start;
        p.end = o.end;
        paddles.push_back(p);
    }
    return paddles;
}

template <int D>
Params<D> make_params(const Scene& scene, const Derived& derived) {
    Params<D> p;
    p.mass = derived.mass;
    p.h = derived.h;
    p.rest_density = scene.material.rest_density;
    p.bulk_modulus = scene.material.bulk_modulus;
    p.spacing = scene.fluid.spacing;
    p.kernel = derived.kernel;
    p.integrator = scene.solver.integrator;
    p.walls = derived.walls;
    p.time_step = time_step_settings(scene);
    p.pressure_solve = {.tolerance = scene.solver.tolerance,
                        .divergence_tolerance = scene.solver.divergence_tolerance,
                        .min_iterations = scene.solver.min_iterations,
                        .max_iterations = scene.solver.max_iterations,
                        .warm_start = scene.solver.warm_start,
                        .warm_start_fraction = scene.solver.warm_start_fraction,
                        .momentum = scene.solver.momentum};
    p.watchdog = {scene.watchdog.retries, scene.watchdog.max_density_ratio,
                  scene.watchdog.max_displacement, derived.max_speed,
                  !scene.watchdog.max_speed.has_value()};
    p.reorder_every =
        scene.solver.reorder_every.value_or(solver_capabilities(scene.solver.name).reorder_every);
    p.rebalance_above = scene.solver.rebalance_above;
    p.precision = derived.precision;
    p.pair_terms = derived.pair_terms;
    // Each solver reads only its own way of carrying the density (as the
    // others ignore solver.artificial_viscosity), so one tank scene serves
    // every solver: delta-SPH for wcsph, solver.density for dfsph.
    if (scene.solver.name == SolverKind::wcsph)
        p.density_diffusion = scene.solver.density_diffusion;
    if (scene.solver.name == SolverKind::dfsph)
        p.density_model = scene.solver.density;
    if (scene.solver.wall_pressure != WallPressure::mirror && scene.effects.gravity &&
        derived.walls == WallModel::particles) {
        p.wall_gravity = to_vec<D>(scene.effects.gravity->acceleration);
        p.wall_pressure = scene.solver.wall_pressure;
    }
    p.domain = {to_vec<D>(scene.domain.min), to_vec<D>(scene.domain.max)};
    p.obstacles = make_obstacles<D>(scene);
    p.paddles = make_paddles<D>(scene);
    // Measured on the 2D flows (docs/benchmarks.md, "Cells that serve
    // several steps"); moving walls would leave the cells' walls behind.
    if (D == 2 && p.precision == Precision::single && p.paddles.empty())
        p.cell_skin = scene.solver.cell_skin.value_or(0.05);
    return p;
}

// The law by which a hydrostatic start compresses the lattice: the solver's
// equation of state (sph/hydrostatic_start.hpp); none where the fluid is
// incompressible or nothing weighs.
StartLaw start_law(const Scene& scene) {
    if (scene.fluid.start != FluidStart::hydrostatic || !scene.effects.gravity)
        return StartLaw::none;
    switch (scene.solver.name) {
    case SolverKind::seed:
        return StartLaw::linear;
    case SolverKind::wcsph:
        return StartLaw::tait;
    default:
        return StartLaw::none;
    }
}

// The blocks' particles, numbered in order: those numbered first to
// first + kept - 1 are kept (all of them with the defaults); `total` is
// set to how many there are.
template <int D>
State<D> lay_initial_state(const Scene& scene, const Derived& derived, std::size_t& total,
                           std::size_t first = 0,
                           std::size_t kept = std::numeric_limits<std::size_t>::max()) {
    const Real s = scene.fluid.spacing;
    const StartLaw law = start_law(scene);
    const Vec<D> gravity =
        scene.effects.gravity ? to_vec<D>(scene.effects.gravity->acceleration) : Vec<D>(0);
    const Real g = glm::length(gravity);
    const Vec<D> up = g > 0 ? -gravity / g : Vec<D>(0);
    // Sites inside an obstacle or a paddle (at rest), or too near one, are
    // left empty: a block may be placed across them.
    std::vector<Obstacle<D>> obstacles = make_obstacles<D>(scene);
    for (const Paddle<D>& paddle : make_paddles<D>(scene))
        obstacles.push_back({ObstacleShape::box, paddle.box, Vec<D>(0), 0, nullptr});
    State<D> state;
    state.resize(std::min(derived.particles, kept));
    std::size_t next = 0;
    for (const auto& block : scene.fluid.blocks) {
        glm::vec<D, std::size_t> count;
        std::size_t total = 1;
        for (int a = 0; a < D; ++a) {
            count[a] = lattice_count(block.min[a], block.max[a], s);
            total *= count[a];
        }
        // The block's filled box (half a spacing beyond its outer sites), its
        // highest and lowest points along `up`: a hydrostatic start's surface
        // and fixed base.
        Real top = 0, bottom = 0;
        for (int a = 0; a < D; ++a) {
            const Real lo = block.min[a], hi = block.min[a] + Real(count[a]) * s;
            top += std::max(up[a] * lo, up[a] * hi);
            bottom += std::min(up[a] * lo, up[a] * hi);
        }
        for (std::size_t k = 0; k < total; ++k) {
            std::size_t rest = k;
            Vec<D> x;
            for (int a = 0; a < D; ++a) {
                x[a] = block.min[a] + (Real(rest % count[a]) + Real(0.5)) * s;
                rest /= count[a];
            }
            if (blocked_by_obstacle<D>(obstacles, x, s))
                continue;
            if (next - first >= kept) { // unsigned: below first too
                ++next;
                continue;
            }
            // 0: the first step sums it; a hydrostatic start gives the
            // density the site carries (read where the density is carried).
            Real density = 0;
            if (law != StartLaw::none) {
                density =
                    hydrostatic_density(law, top - glm::dot(x, up), g, scene.material.rest_density,
                                        scene.material.bulk_modulus);
                x = hydrostatic_site<D>(x, up, top, bottom, law, g, scene.material.rest_density,
                                        scene.material.bulk_modulus);
            }
            const std::size_t i = next - first;
            state.position[i] = x;
            state.density[i] = density;
            state.velocity[i] = to_vec<D>(block.velocity);
            state.acceleration[i] = Vec<D>(0);
            state.id[i] = static_cast<std::uint32_t>(next);
            ++next;
        }
    }
    if (next == 0)
        throw InputError(scene.file, "effects.obstacles",
                         "every fluid particle of the blocks lies inside an obstacle (or within "
                         "half a spacing of one)");
    total = next;
    state.resize(std::min(next - std::min(next, first), kept));
    return state;
}

template <int D>
State<D> make_initial_state(const Scene& scene, const Derived& derived) {
    std::size_t total = 0;
    return lay_initial_state<D>(scene, derived, total);
}

// Over processes, this process's share of the initial state alone: the
// particles are counted first (laid, none kept), then its run laid.
template <int D>
State<D> make_initial_share(const Scene& scene, const Derived& derived, Partition<D>& partition) {
    std::size_t total = 0;
    lay_initial_state<D>(scene, derived, total, 0, 0);
    const auto share = partition.starting_share(total);
    return lay_initial_state<D>(scene, derived, total, share.first, share.count);
}

template <int D>
EffectList<D> make_effects(const Scene& scene) {
    EffectList<D> effects;
    for_each_effect(scene.effects,
                    [&](const auto& settings) { effects.push_back(make_effect<D>(settings)); });
    return effects;
}

template <int D>
SourceList<D> make_sources(const Scene& scene) {
    SourceList<D> sources;
    for (std::size_t index = 0; index < scene.effects.emitters.size(); ++index) {
        const SceneEmitter& e = scene.effects.emitters[index];
        // The box's lattice, as for a fluid block; its thickness along v.
        const Real spacing = scene.fluid.spacing;
        const Vec<D> velocity = to_vec<D>(e.velocity);
        const Vec<D> along = velocity / glm::length(velocity);
        glm::vec<D, std::size_t> count;
        std::size_t total = 1;
        Real thickness = 0;
        for (int a = 0; a < D; ++a) {
            count[a] = lattice_count(e.min[a], e.max[a], spacing);
            total *= count[a];
            thickness += std::abs(along[a]) * Real(count[a]) * spacing;
        }
        // A disc inlet keeps the sites within its radius of the axis.
        const Vec<D> centre = (to_vec<D>(e.min) + to_vec<D>(e.max)) / Real(2);
        std::vector<Vec<D>> sites;
        sites.reserve(total);
        for (std::size_t k = 0; k < total; ++k) {
            std::size_t rest = k;
            Vec<D> x;
            for (int a = 0; a < D; ++a) {
                x[a] = e.min[a] + (Real(rest % count[a]) + Real(0.5)) * spacing;
                rest /= count[a];
            }
            const Vec<D> off = x - centre;
            if (!e.radius || glm::length(off - glm::dot(off, along) * along) <= *e.radius)
                sites.push_back(x);
        }
        if (sites.empty())
            throw InputError(scene.file, fmt::format("effects.emitters[{}].radius", index),
                             fmt::format("no lattice site of the box lies within {} m of its "
                                         "axis; give a radius of at least half a spacing ({} m)",
                                         *e.radius, spacing / 2));
        sources.push_back(std::make_unique<Emitter<D>>(Box<D>{to_vec<D>(e.min), to_vec<D>(e.max)},
                                                       spacing, std::move(sites), velocity,
                                                       thickness, e.start, e.end));
    }
    return sources;
}

template <int D>
Simulation<D> make_simulation(const Scene& scene, const Derived& derived,
                              const PartitionMaker<D>& partition) {
    const Params<D> params = make_params<D>(scene, derived);
    EffectList<D> effects = make_effects<D>(scene);
    std::unique_ptr<Partition<D>> shared = partition ? partition(params, effects) : nullptr;
    State<D> initial = shared ? make_initial_share<D>(scene, derived, *shared)
                              : make_initial_state<D>(scene, derived);
    return Simulation<D>(params, std::move(initial), make_solver<D>(scene.solver.name, params),
                         make_neighbour_search<D>(scene.solver.neighbour_search),
                         std::move(effects), make_sources<D>(scene), std::move(shared));
}

template std::vector<Paddle<2>> make_paddles<2>(const Scene&);
template std::vector<Paddle<3>> make_paddles<3>(const Scene&);
template Params<2> make_params<2>(const Scene&, const Derived&);
template Params<3> make_params<3>(const Scene&, const Derived&);
template State<2> make_initial_state<2>(const Scene&, const Derived&);
template State<3> make_initial_state<3>(const Scene&, const Derived&);
template EffectList<2> make_effects<2>(const Scene&);
template EffectList<3> make_effects<3>(const Scene&);
template SourceList<2> make_sources<2>(const Scene&);
template SourceList<3> make_sources<3>(const Scene&);
template Simulation<2> make_simulation<2>(const Scene&, const Derived&, const PartitionMaker<2>&);
template Simulation<3> make_simulation<3>(const Scene&, const Derived&, const PartitionMaker<3>&);

} // namespace sph
