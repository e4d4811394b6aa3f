// sphclip_bench_step: what a whole step costs. A dam-break block (a wide, 2a
// high, a deep in 3D) at rest in a box (3a x 2.4a x a) is stepped with a
// fixed dt by each solver, in 2D and 3D, at 10k, 100k and 1M particles, with
// 1 and 2 threads. The lattice spacing is the same at every size (1 mm; the
// block and the box grow with the count), so one dt (2e-5 s, under the CFL
// limit of the smallest support) is stable everywhere and every configuration
// of a size runs the same steps. Scene defaults otherwise: gravity, viscosity
// 1 Pa.s, the solver's walls (reflecting for seed, wall particles for wcsph
// and dfsph), with each neighbour search (sorted_grid, the default, and hash)
// and with the particle arrays sorted by cell every few steps or never
// (solver.reorder_every; "+reorderN" after the search's name, nothing: never).
//
// Then the "DualSPHysics-comparable" case: the 2D wcsph dam break with the
// Wendland C2 kernel, support 2.82 dp (20 neighbours on the lattice, 21 with
// the particle itself), the Verlet integrator, artificial viscosity only,
// ~21,000 fluid particles, with each search (--search) and reordering; its rate is compared
// with DualSPHysics 5.0's ~0.6 M particle-steps/s (2 threads, same machine).
//
// With --shuffled, every case runs again from particle arrays in a random
// (fixed) order, as after the particles of a long run have mixed: what the
// sort by cell is for ("-shuffled" after the case's name).
//
// Per configuration: wall time of the timed steps (after one untimed warm-up
// step that sizes every array), particle-steps per second, the split by stage
// (Simulation::stage_times()), neighbours per particle, memory per particle
// (the state and neighbour-list arrays; the rise of the peak resident set
// over the resident set before the set-up) and the peak resident set, and
// whether the 2-thread run ends on the same state hash as the 1-thread run.
// A program that prints a table, not a timed test (docs/benchmarks.md).
//
//   sphclip_bench_step [--quick|--tiny] [--sizes 10000,100000] [--solvers seed,wcsph]
//                      [--dims 2,3] [--threads 1,2] [--steps N] [--search hash,sorted_grid]
//                      [--reorder 0,20] [--shuffled] [--no-dsph] [--csv FILE]

#include "bench_support.hpp"
#include "scene/scene_setup.hpp"
#include "sph/single_precision/single_passes.hpp"
#include "sph/snapshot.hpp"
#include "sph/state_hash.hpp"
#include "sph/vector_clones.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fmt/format.h>
#include <fstream>
#include <numeric>
#include <omp.h>
#include <string>
#include <thread>
#include <vector>

using namespace sph;

namespace {

// The lattice spacing at every size, and the step: 0.4 h / c with the
// smallest support (2.2 dp in 3D) and c = sqrt(2e5 / 1000) = 14.1 m/s is
// 6e-5 s.
constexpr double spacing = 1e-3; // m
constexpr double dt = 2e-5;      // s
// DualSPHysics 5.0, its 2D dam-break validation case, 2 threads on this
// machine (docs/benchmarks.md, "Against DualSPHysics").
constexpr double dualsphysics_rate = 0.6e6; // particle-steps/s

// Restarts the peak resident set (VmHWM) from the current one (Linux 4.0+).
void reset_peak_rss() {
    if (std::FILE* f = std::fopen("/proc/self/clear_refs", "w")) {
        std::fputs("5", f);
        std::fclose(f);
    }
}

struct Case {
    std::string solver;
    int dimension = 2;
    std::size_t target = 0; // particles asked for
    std::string search;
    bool dsph = false; // the DualSPHysics-comparable case
    int steps = 0;
    int reorder = 0; // solver.reorder_every
    bool shuffled = false;
    std::string precision = "auto"; // solver.precision

    // The search's name, with the reordering when there is one, and
    // "+single" when the passes run in single precision (cells, no lists).
    std::string search_label(Precision resolved_precision) const {
        const std::string label =
            reorder > 0 ? fmt::format("{}+reorder{}", search, reorder) : search;
        return resolved_precision == Precision::single ? label + "+single" : label;
    }
};

struct Stage {
    std::string name;
    double seconds = 0;
};

struct Result {
    std::size_t particles = 0, boundary = 0;
    int threads = 0;
    std::uint64_t steps = 0, retries = 0;
    double setup_s = 0, wall_s = 0, neighbours = 0;
    double array_bytes = 0, rss_bytes = 0, peak_rss = 0;
    std::uint64_t hash = 0;
    std::vector<Stage> stages; // timed steps only, largest first

    double particle_steps() const { return double(particles) * double(steps); }
    double rate() const { return particle_steps() / wall_s; }
};

std::vector<Override> overrides(const Case& c) {
    // Particles per axis of the block: n x 2n (x n in 3D).
    const double n =
        c.dimension == 2 ? std::sqrt(double(c.target) / 2) : std::cbrt(double(c.target) / 2);
    const double a = std::max(1.0, std::round(n)) * spacing;
    const auto num = [](double v) {
        return fmt::format("{:.17g}", v);
    };
    const bool three = c.dimension == 3;
    const std::string origin = three ? "[0, 0, 0]" : "[0, 0]";
    const std::string depth = three ? fmt::format(", {:.17g}", a) : std::string();
    std::vector<Override> o{
        {"dimension", std::to_string(c.dimension)},
        {"solver.name", c.solver},
        {"solver.dt", num(dt)},
        {"solver.neighbour_search", c.search},
        {"solver.reorder_every", std::to_string(c.reorder)},
        {"solver.precision", c.precision},
        {"fluid.spacing", num(spacing)},
        {"domain.min", origin},
        {"domain.max", fmt::format("[{:.17g}, {:.17g}{}]", 3 * a, 2.4 * a, depth)},
        {"fluid.blocks",
         fmt::format("[{{\"min\": {}, \"max\": [{:.17g}, {:.17g}{}]}}]", origin, a, 2 * a, depth)},
    };
    if (c.dsph) {
        // DualSPHysics' case: Wendland C2, h = 1.41 dp (support 2.82 dp),
        // Verlet, artificial viscosity (alpha 0.02 here), no laminar viscosity.
        o.push_back({"solver.kernel", "wendland_c2"});
        o.push_back({"fluid.smoothing_ratio", "2.82"});
        o.push_back({"solver.integrator", "verlet"});
        o.push_back({"material.viscosity", "0"});
    }
    return o;
}

// A random order, the same on every run (no library distribution: their
// algorithms differ between standard libraries).
template <int D>
void shuffle(State<D>& state) {
    std::vector<std::uint32_t> order(state.size());
    std::iota(order.begin(), order.end(), 0u);
    std::uint64_t x = 0x9e3779b97f4a7c15u;
    for (std::size_t k = order.size(); k > 1; --k) {
        x ^= x << 13; // xorshift64
        x ^= x >> 7;
        x ^= x << 17;
        std::swap(order[k - 1], order[x % k]);
    }
    PermuteScratch<D> scratch;
    state.permute(order, scratch);
}

template <int D>
Result run(const Scene& scene, int threads, int steps, bool shuffled) {
    omp_set_num_threads(threads);
    Result r;
    r.threads = threads;
    const double rss_before = bench::status_bytes("VmRSS");
    reset_peak_rss();
    const auto setup_start = std::chrono::steady_clock::now();
    auto sim = make_simulation<D>(scene);
    if (shuffled)
        shuffle(sim.state());
    sim.step(); // warm-up: neighbour lists, scratch and the watchdog's copy sized
    r.setup_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count();
    const std::vector<StageTimes::Entry> before = sim.stage_times().entries();
    const std::uint64_t steps_before = sim.steps();
    sim.take_counters();
    const auto start = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k)
        sim.step();
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.steps = sim.steps() - steps_before;
    r.retries = sim.take_counters().retries;
    r.particles = sim.state().size();
    r.boundary = sim.boundary() ? sim.boundary()->size() : 0;
    for (const auto& e : sim.stage_times().entries()) {
        double earlier = 0;
        for (const auto& b : before)
            if (b.name == e.name)
                earlier = b.seconds;
        r.stages.push_back({std::string(e.name), e.seconds - earlier});
    }
    std::sort(r.stages.begin(), r.stages.end(),
              [](const Stage& a, const Stage& b) { return a.seconds > b.seconds; });
    // Single-precision steps build no lists: update_fields (untimed) does.
    sim.update_fields();
    const NeighbourList& list = sim.neighbours();
    r.neighbours = list.particle_count() ? double(list.pair_count()) / list.particle_count() : 0;
    // The state's arrays (with the watchdog's copy of them) and the fluid
    // neighbour list; solver scratch and the wall particles' lists are not
    // reachable from here, the resident set counts them.
    double bytes = 0;
    sim.state().for_each_array(
        [&](auto& array) { bytes += 2.0 * double(array.capacity() * sizeof(array[0])); });
    bytes += double((list.start.capacity() + list.index.capacity()) * sizeof(std::uint32_t));
    r.array_bytes = bytes / double(r.particles);
    r.peak_rss = bench::status_bytes("VmHWM");
    r.rss_bytes = (r.peak_rss - rss_before) / double(r.particles);
    Snapshot frame;
    copy_fields(sim.state(), frame);
    r.hash = state_hash(frame);
    return r;
}

std::string stage_summary(const Result& r, std::size_t count) {
    std::string text;
    double staged = 0;
    for (const auto& s : r.stages)
        staged += s.seconds;
    for (std::size_t k = 0; k < r.stages.size() && k < count; ++k)
        text += fmt::format("{}{} {:.0f}%", k ? ", " : "", r.stages[k].name,
                            100 * r.stages[k].seconds / r.wall_s);
    const double other = r.wall_s - staged;
    if (other > 0.005 * r.wall_s)
        text += fmt::format(", untimed {:.0f}%", 100 * other / r.wall_s);
    return text;
}

std::string stage_csv(const Result& r) {
    std::string text;
    for (const auto& s : r.stages)
        text += fmt::format("{}{}={:.1f}", text.empty() ? "" : ";", s.name,
                            s.seconds * 1e9 / r.particle_steps());
    return text;
}

std::string machine() {
    return fmt::format("{}, {} cores (hardware_concurrency), {}, compiler {}, single-precision "
                       "passes {}, double-precision passes {}, load average at start {}",
                       bench::now_utc("%Y-%m-%d %H:%M"), std::thread::hardware_concurrency(),
                       bench::cpu_model(), __VERSION__,
                       fmt::format("{} ({})", simd_variant(), simd_instructions()),
                       vector_clone_variant(), bench::load_average());
}

int usage() {
    fmt::print(stderr,
               "usage: sphclip_bench_step [--quick|--tiny] [--sizes N,N] [--solvers "
               "seed,wcsph,dfsph] [--dims 2,3] [--threads 1,2] [--steps N] [--search "
               "hash,sorted_grid] [--reorder 0,20] [--precision auto,single,double] [--shuffled] "
               "[--no-dsph] [--csv FILE]\n");
    return 2;
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false, dsph = true, shuffled = false;
    int steps = 0; // 0: by size (below)
    std::vector<std::size_t> sizes{10000, 100000, 1000000};
    std::vector<std::string> solvers{"seed", "wcsph", "dfsph"};
    std::vector<int> dims{2, 3}, thread_counts{1, 2};
    std::vector<std::string> searches{"sorted_grid", "hash"};
    std::vector<int> reorders{0, 20}; // never, and seed's and wcsph's default
    std::vector<std::string> precisions{"auto"};
    std::FILE* csv = nullptr;
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        const bool has_value = k + 1 < argc;
        if (arg == "--quick" || arg == "--tiny") {
            quick = true;
        } else if (arg == "--no-dsph") {
            dsph = false;
        } else if (arg == "--shuffled") {
            shuffled = true;
        } else if (arg == "--sizes" && has_value) {
            sizes.clear();
            for (const auto& s : bench::split_list(argv[++k]))
                sizes.push_back(std::strtoull(s.c_str(), nullptr, 10));
        } else if (arg == "--solvers" && has_value) {
            solvers = bench::split_list(argv[++k]);
        } else if (arg == "--dims" && has_value) {
            dims.clear();
            for (const auto& s : bench::split_list(argv[++k]))
                dims.push_back(std::atoi(s.c_str()));
        } else if (arg == "--threads" && has_value) {
            thread_counts.clear();
            for (const auto& s : bench::split_list(argv[++k]))
                thread_counts.push_back(std::atoi(s.c_str()));
        } else if (arg == "--steps" && has_value) {
            steps = std::atoi(argv[++k]);
        } else if (arg == "--search" && has_value) {
            searches = bench::split_list(argv[++k]);
        } else if (arg == "--reorder" && has_value) {
            reorders.clear();
            for (const auto& s : bench::split_list(argv[++k]))
                reorders.push_back(std::atoi(s.c_str()));
        } else if (arg == "--precision" && has_value) {
            precisions = bench::split_list(argv[++k]);
        } else if (arg == "--csv" && has_value) {
            csv = std::fopen(argv[++k], "w");
            if (!csv)
                return 2;
        } else {
            return usage();
        }
    }
    if (quick) {
        sizes = {300};
        if (steps == 0)
            steps = 2;
    }
    for (int d : dims)
        if (d != 2 && d != 3)
            return usage();
    // Steps by size when not given: fewer for the large sizes, so that the
    // default run takes minutes (a step of 1M particles in 3D takes 5-10 s
    // with the hash search on 2 cores). Every configuration of a size runs
    // the same steps.
    const auto steps_for = [&](std::size_t n) {
        return steps > 0 ? steps : n <= 20000 ? 50 : n <= 200000 ? 10 : 3;
    };
    std::vector<Case> cases;
    for (const auto& precision : precisions)
        for (const auto& search : searches)
            for (int reorder : reorders)
                for (const auto& solver : solvers)
                    for (int d : dims)
                        for (std::size_t n : sizes)
                            cases.push_back({solver, d, n, search, false, steps_for(n), reorder,
                                             false, precision});
    if (dsph)
        for (const auto& precision : precisions)
            for (const auto& s : searches)
                for (int reorder : reorders)
                    cases.push_back({"wcsph", 2, quick ? 300u : 21000u, s, true,
                                     steps > 0 ? steps : 200, reorder, false, precision});
    if (shuffled)
        for (std::size_t k = 0, count = cases.size(); k < count; ++k) {
            cases.push_back(cases[k]);
            cases.back().shuffled = true;
        }

    const std::string header = machine();
    fmt::print("full-step benchmark: {}\nfixed dt {} s, spacing {} m, one warm-up step "
               "untimed; particles are fluid particles (wall particles extra)\n\n",
               header, dt, spacing);
    fmt::print("| case | solver | D | search | particles | walls | threads | steps | wall s | "
               "M particle-steps/s | ns / particle-step | neighbours | B / particle (arrays, "
               "RSS) | peak RSS MB | same hash as 1 thread | top stages |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    if (csv) {
        fmt::print(csv,
                   "# sphclip_bench_step, {}\n# fixed dt {} s, spacing {} m, one warm-up "
                   "step untimed; stages: ns per particle-step\n",
                   header, dt, spacing);
        fmt::print(csv, "case,solver,dimension,search,particles,boundary_particles,threads,steps,"
                        "retries,setup_s,wall_s,particle_steps_per_s,ns_per_particle_step,"
                        "neighbours_per_particle,array_bytes_per_particle,rss_bytes_per_particle,"
                        "peak_rss_mb,state_hash,same_hash_as_1_thread,stages\n");
    }
    bool all_same = true;
    std::vector<double> dsph_rates;
    for (const auto& c : cases) {
        const Scene scene = default_scene(overrides(c));
        const std::string search_label = c.search_label(derive(scene).precision);
        std::uint64_t first_hash = 0;
        bool have_first = false;
        for (int threads : thread_counts) {
            const Result r = c.dimension == 2 ? run<2>(scene, threads, c.steps, c.shuffled)
                                              : run<3>(scene, threads, c.steps, c.shuffled);
            if (!have_first) {
                first_hash = r.hash;
                have_first = true;
            }
            const bool same = r.hash == first_hash;
            all_same = all_same && same;
            const std::string label =
                std::string(c.dsph ? "dsph-like" : "grid") + (c.shuffled ? "-shuffled" : "");
            const std::string same_text = threads == thread_counts.front() ? "-"
                                          : same                           ? "yes"
                                                                           : "NO";
            fmt::print("| {} | {} | {} | {} | {} | {} | {} | {} | {:.2f} | {:.3f} | {:.0f} | "
                       "{:.1f} | {:.0f}, {:.0f} | {:.0f} | {} | {} |\n",
                       label, c.solver, c.dimension, search_label, r.particles, r.boundary, threads,
                       r.steps, r.wall_s, r.rate() * 1e-6, 1e9 / r.rate(), r.neighbours,
                       r.array_bytes, r.rss_bytes, r.peak_rss / 1048576, same_text,
                       stage_summary(r, 4));
            if (c.dsph)
                fmt::print("|   | ratio to DualSPHysics' 0.6 M/s: {:.2f}x (goal 3x) |\n",
                           r.rate() / dualsphysics_rate);
            if (r.retries)
                fmt::print("|   | watchdog retries: {} (the dt was too long) |\n", r.retries);
            if (csv) {
                fmt::print(csv,
                           "{},{},{},{},{},{},{},{},{},{:.3f},{:.4f},{:.0f},{:.1f},{:.2f},{:.0f},"
                           "{:.0f},{:.1f},{:016x},{},\"{}\"\n",
                           label, c.solver, c.dimension, search_label, r.particles, r.boundary,
                           threads, r.steps, r.retries, r.setup_s, r.wall_s, r.rate(),
                           1e9 / r.rate(), r.neighbours, r.array_bytes, r.rss_bytes,
                           r.peak_rss / 1048576, r.hash, same_text, stage_csv(r));
                std::fflush(csv);
            }
            std::fflush(stdout);
        }
    }
    // Another program running meanwhile slows the 2-thread runs most.
    fmt::print("\nload average at the end {}\n", bench::load_average());
    if (csv) {
        fmt::print(csv, "# load average at the end {}\n", bench::load_average());
        std::fclose(csv);
    }
    fmt::print("{}\n", all_same ? "every thread count gave the same state hash"
                                : "THREAD COUNTS DISAGREE on the state hash (see NO above)");
    return all_same ? 0 : 1;
}
