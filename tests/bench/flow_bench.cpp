// sphclip_bench_flow: what a step costs in the flows users run, with the
// particles in the order a run leaves them (issue 22, item 1).
//
// Each case is a shipped scene at a given resolution. It is first run
// (untimed, 2 threads, the scene's own settings) to a start time after the
// flow is under way: the dam-break column collapsing, the surge running
// along the floor. That state, velocities and particle order included, is
// the start of every timed configuration: precision (single cells or double
// lists), thread count and reordering interval, each stepping the same
// number of adaptive steps as `sphclip run` takes them. The configurations
// are interleaved over --rounds rounds, so a change in the machine's load
// reaches all of them alike; the table gives each one's median and range.
//
// With --load N, N busy processes (a tight loop each, niced 0, like a
// compile job) run for the whole measurement: the "under load" rows of
// issue 22's item 4. The OpenMP wait policy in force (OMP_WAIT_POLICY,
// GOMP_SPINCOUNT, or sphclip's own default, cli/wait_policy.hpp) is printed
// with the machine, since it decides what a busy machine costs.
//
// A program that prints a table, not a timed test (docs/benchmarks.md).
//
//   sphclip_bench_flow [--tiny] [--cases NAME,NAME] [--threads 1,2,auto]
//                      [--precision single,double] [--reorder N,N] [--steps N]
//                      [--rounds N] [--load N] [--scenes DIR] [--csv FILE]

#include "bench_support.hpp"
#include "parallel/thread_count_tuner.hpp"
#include "scene/scene_setup.hpp"
#include "sph/single_precision/single_passes.hpp"
#include "sph/snapshot.hpp"
#include "sph/state_hash.hpp"
#include "sph/vector_clones.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <map>
#include <omp.h>
#include <optional>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace sph;
using namespace sph::bench;

namespace {

// One flow: a shipped scene, its resolution, when the timing starts.
struct FlowCase {
    std::string name;
    std::string scene_file; // under --scenes
    std::vector<Override> overrides;
    double start = 0; // s, simulated before timing
    int steps = 0;    // timed steps
};

// The Martin & Moyce column of the water scenes: width a, height 2a.
constexpr double column = 0.05715; // m

std::string number(double v) {
    return fmt::format("{:.17g}", v);
}

// Spacing giving about n particles in the a x 2a column (x 0.1 m in 3D).
double spacing_for(int dimension, double n) {
    return dimension == 2 ? std::sqrt(column * 2 * column / n)
                          : std::cbrt(column * 2 * column * 0.1 / n);
}

std::vector<FlowCase> all_cases() {
    const auto water_2d = [](double n) {
        return std::vector<Override>{{"fluid.spacing", number(spacing_for(2, n))}};
    };
    // DualSPHysics's settings on the same column: Wendland C2 with
    // h = 1.41 dp (support 2.82 dp), Verlet, Monaghan's alpha 0.02 and no
    // laminar viscosity (the conditions of issue 22's side-by-side table).
    const auto dsph_2d = [](double n) {
        return std::vector<Override>{{"fluid.spacing", number(spacing_for(2, n))},
                                     {"solver.kernel", "wendland_c2"},
                                     {"fluid.smoothing_ratio", "2.82"},
                                     {"solver.integrator", "verlet"},
                                     {"solver.artificial_viscosity", "0.02"},
                                     {"material.viscosity", "0"}};
    };
    return {
        {"dam_2d_5k", "dam_break_water_2d.json", water_2d(5000), 0.1, 400},
        {"dam_2d_20k", "dam_break_water_2d.json", water_2d(20000), 0.1, 200},
        // The surge on the floor, near the far wall: the particles have
        // mixed more, the free surface is long and thin.
        {"surge_2d_5k", "dam_break_water_2d.json", water_2d(5000), 0.35, 400},
        {"dsph_2d_5k", "dam_break_water_2d.json", dsph_2d(5000), 0.1, 400},
        {"dsph_2d_20k", "dam_break_water_2d.json", dsph_2d(20000), 0.1, 200},
        {"dfsph_2d_5k", "dam_break_water_2d_dfsph.json", water_2d(5000), 0.1, 60},
        {"dam_3d_100k",
         "dam_break_water_3d.json",
         {{"fluid.spacing", number(spacing_for(3, 100000))}},
         0.05,
         20},
        {"dfsph_3d_100k",
         "dam_break_water_3d_dfsph.json",
         {{"fluid.spacing", number(spacing_for(3, 100000))}},
         0.05,
         5},
    };
}

// A tiny version of each case for the ctest that keeps the program working.
FlowCase tiny(FlowCase c) {
    const int dimension = c.name.find("_3d") != std::string::npos ? 3 : 2;
    for (auto& o : c.overrides)
        if (o.key == "fluid.spacing")
            o.value = number(spacing_for(dimension, dimension == 2 ? 300 : 1000));
    c.start = 0.01;
    c.steps = 3;
    return c;
}

struct Config {
    std::string precision; // single, double
    int threads = 1;
    int reorder = -1; // -1: the scene's
    std::string label() const {
        const std::string count = threads > 0 ? fmt::format("x{}", threads) : "auto";
        return reorder < 0 ? fmt::format("{} {}", precision, count)
                           : fmt::format("{} {} reorder{}", precision, count, reorder);
    }
};

struct Sample {
    double wall_s = 0;
    std::uint64_t particle_steps = 0;
    std::uint64_t hash = 0;
    std::map<std::string, double> stage_s;
    std::uint64_t steps = 0;
    SolveWork solves; // dfsph's iterations in the timed steps
    double rate() const { return double(particle_steps) / wall_s; }
};

std::vector<Override> with_config(std::vector<Override> o, const Config& c) {
    o.push_back({"solver.precision", c.precision});
    if (c.reorder >= 0)
        o.push_back({"solver.reorder_every", std::to_string(c.reorder)});
    return o;
}

// threads 0: `sphclip run`'s default, the count chosen as the run goes
// (parallel/thread_count_tuner.hpp), from all cores or the cores the
// kernel counts free.
template <int D>
Sample time_steps(const Scene& scene, const State<D>& start, int threads, int steps) {
    const int cores = int(std::thread::hardware_concurrency());
    omp_set_num_threads(threads > 0 ? threads : cores);
    auto sim = make_simulation<D>(scene);
    sim.state() = start;
    sim.step(); // untimed: every array and list sized for this state
    const auto before = sim.stage_times().entries();
    const std::uint64_t particle_steps_before = sim.particle_steps(), steps_before = sim.steps();
    const SolveWork solves_before = sim.solve_work();
    std::optional<parallel::ThreadCountTuner> tuner;
    if (threads == 0)
        tuner.emplace(cores, parallel::free_cores_of_this_machine());
    const auto t0 = std::chrono::steady_clock::now();
    for (int k = 0; k < steps; ++k) {
        if (!tuner) {
            sim.step();
            continue;
        }
        tuner->step([&] {
            const std::uint64_t done = sim.particle_steps();
            sim.step();
            return sim.particle_steps() - done;
        });
    }
    Sample s;
    s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    s.particle_steps = sim.particle_steps() - particle_steps_before;
    s.steps = sim.steps() - steps_before;
    s.solves.pressure = sim.solve_work().pressure - solves_before.pressure;
    s.solves.pressure_iterations =
        sim.solve_work().pressure_iterations - solves_before.pressure_iterations;
    for (const auto& e : sim.stage_times().entries()) {
        double earlier = 0;
        for (const auto& b : before)
            if (b.name == e.name)
                earlier = b.seconds;
        s.stage_s[std::string(e.name)] = e.seconds - earlier;
    }
    Snapshot frame;
    copy_fields(sim.state(), frame);
    s.hash = state_hash(frame);
    return s;
}

// Mean neighbours a fluid particle has within the support radius h, fluid
// and wall particles alike: the pairs a step's sums run over, counted from
// the positions alone so that single-precision cells, double-precision
// lists, 2D and 3D are counted the same way (issue 22, item 5: the cost
// per pair, 3D against 2D).
template <int D>
double neighbours_per_particle(const Simulation<D>& sim) {
    const Real h = sim.params().h;
    std::vector<Vec<D>> points(sim.state().position.begin(), sim.state().position.end());
    if (const auto* walls = sim.boundary())
        points.insert(points.end(), walls->positions().begin(), walls->positions().end());
    // Cells of side h: a pair closer than h lies in neighbouring cells.
    std::map<std::array<long, D>, std::vector<std::size_t>> cells;
    const auto cell_of = [&](const Vec<D>& x) {
        std::array<long, D> c;
        for (int a = 0; a < D; ++a)
            c[a] = long(std::floor(x[a] / h));
        return c;
    };
    for (std::size_t k = 0; k < points.size(); ++k)
        cells[cell_of(points[k])].push_back(k);
    std::uint64_t pairs = 0;
    const std::size_t fluid = sim.state().size();
    for (std::size_t i = 0; i < fluid; ++i) {
        const auto home = cell_of(points[i]);
        for (int around = 0; around < (D == 2 ? 9 : 27); ++around) {
            std::array<long, D> c = home;
            for (int a = 0, code = around; a < D; ++a, code /= 3)
                c[a] += code % 3 - 1;
            const auto found = cells.find(c);
            if (found == cells.end())
                continue;
            for (std::size_t j : found->second)
                pairs += j != i && squared_length(points[j] - points[i]) < h * h;
        }
    }
    return fluid ? double(pairs) / double(fluid) : 0;
}

std::string environment(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "(unset)";
}

// The busy processes of --load: children spinning until killed.
class CompetingLoad {
  public:
    explicit CompetingLoad(int count) {
        for (int k = 0; k < count; ++k) {
            const pid_t pid = fork();
            if (pid == 0) {
                volatile std::uint64_t x = 0;
                for (;;)
                    x = x + 1;
            }
            if (pid > 0)
                children_.push_back(pid);
        }
    }
    ~CompetingLoad() {
        for (pid_t pid : children_)
            kill(pid, SIGKILL);
        for (pid_t pid : children_)
            waitpid(pid, nullptr, 0);
    }

  private:
    std::vector<pid_t> children_;
};

int usage() {
    std::string names;
    for (const auto& c : all_cases())
        names += (names.empty() ? "" : ",") + c.name;
    fmt::print(stderr,
               "usage: sphclip_bench_flow [--tiny] [--cases {}] [--threads 1,2,auto] [--precision "
               "single,double] [--reorder N,N] [--steps N] [--rounds N] [--load N] [--scenes DIR] "
               "[--csv FILE]\n",
               names);
    return 2;
}

template <int D>
int run_case(const FlowCase& c, const std::string& scenes, const std::vector<Config>& configs,
             int rounds, std::FILE* csv) {
    const std::string file = scenes + "/" + c.scene_file;
    // The warm-up: the scene's own settings, as `sphclip run` would step it.
    omp_set_num_threads(2);
    const Scene warm_scene = load_scene(file, c.overrides);
    auto warm = make_simulation<D>(warm_scene);
    const auto warm_start = std::chrono::steady_clock::now();
    warm.advance_to(c.start);
    const double warm_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - warm_start).count();
    const State<D> start = warm.state();
    const double neighbours = neighbours_per_particle(warm);
    fmt::print("\n### {}: {} particles ({}D, {}), from t = {} s ({} steps, {:.1f} s to get "
               "there), {} steps timed, {:.1f} neighbours a particle within h\n\n",
               c.name, start.size(), D, c.scene_file, c.start, warm.steps(), warm_s, c.steps,
               neighbours);
    fmt::print("| configuration | M particle-steps/s (median) | range | ns / particle-step | "
               "ns / pair | same hash as x1 | top stages (ns / particle-step) "
               "|\n|---|---|---|---|---|---|---|\n");

    std::vector<std::vector<Sample>> samples(configs.size());
    std::vector<bool> runs(configs.size(), true);
    for (int round = 0; round < rounds; ++round)
        for (std::size_t k = 0; k < configs.size(); ++k) {
            if (!runs[k])
                continue;
            try {
                const Scene scene = load_scene(file, with_config(c.overrides, configs[k]));
                samples[k].push_back(time_steps<D>(scene, start, configs[k].threads, c.steps));
            } catch (const std::exception& e) {
                // single precision where the scene cannot have it (dfsph)
                fmt::print("| {} | not run: {} |\n", configs[k].label(), e.what());
                runs[k] = false;
            }
        }
    for (std::size_t k = 0; k < configs.size(); ++k) {
        if (samples[k].empty())
            continue;
        std::vector<double> rates;
        for (const auto& s : samples[k])
            rates.push_back(s.rate());
        const double m = median(rates);
        const auto [lo, hi] = std::minmax_element(rates.begin(), rates.end());
        // The same hash as the one-thread run of the same precision and
        // reordering: bit-identical threads, in a flow.
        std::string same = "-";
        for (std::size_t j = 0; j < configs.size(); ++j)
            if (j != k && configs[j].threads == 1 && configs[k].threads != 1 &&
                configs[j].precision == configs[k].precision &&
                configs[j].reorder == configs[k].reorder && !samples[j].empty())
                same = samples[j].front().hash == samples[k].front().hash ? "yes" : "NO";
        // Stages of the median-like sample: the first round's order is fine
        // for the split, which changes little between rounds.
        const Sample& s = samples[k][samples[k].size() / 2];
        std::vector<std::pair<double, std::string>> stages;
        for (const auto& [name, seconds] : s.stage_s)
            stages.push_back({seconds, name});
        std::sort(stages.rbegin(), stages.rend());
        std::string top, all;
        for (std::size_t j = 0; j < stages.size(); ++j) {
            const double ns = stages[j].first * 1e9 / double(s.particle_steps);
            if (j < 4)
                top += fmt::format("{}{} {:.0f}", j ? ", " : "", stages[j].second, ns);
            // dfsph's density solve: iterations a step, ns a particle-iteration.
            if (j < 4 && stages[j].second == "pressure solve" && s.solves.pressure > 0)
                top += fmt::format(" ({:.1f} it x {:.1f})",
                                   double(s.solves.pressure_iterations) / double(s.steps),
                                   stages[j].first * 1e9 / double(s.solves.pressure));
            all += fmt::format("{}{}={:.1f}", j ? ";" : "", stages[j].second, ns);
        }
        const double ns_per_pair = neighbours > 0 ? 1e9 / m / neighbours : 0;
        fmt::print("| {} | {:.3f} | {:.3f}-{:.3f} | {:.0f} | {:.2f} | {} | {} |\n",
                   configs[k].label(), m * 1e-6, *lo * 1e-6, *hi * 1e-6, 1e9 / m, ns_per_pair, same,
                   top);
        if (csv)
            fmt::print(
                csv,
                "{},{},{},{},{},{},{},{},{:.0f},{:.0f},{:.0f},{:.1f},{:.2f},{:.3f},{},\"{}\"\n",
                c.name, D, start.size(), configs[k].precision, configs[k].threads,
                configs[k].reorder, c.steps, samples[k].size(), m, *lo, *hi, 1e9 / m, neighbours,
                ns_per_pair, same, all);
    }
    std::fflush(stdout);
    if (csv)
        std::fflush(csv);
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::string> names{"dam_2d_5k",  "dam_2d_20k",  "surge_2d_5k",
                                   "dsph_2d_5k", "dsph_2d_20k", "dam_3d_100k"};
    std::vector<int> thread_counts{1, 2}, reorders{-1};
    std::vector<std::string> precisions{"single", "double"};
    int steps = 0, rounds = 3, load = 0;
    bool small = false;
    std::string scenes = SPHCLIP_SCENES_DIR;
    std::FILE* csv = nullptr;
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        const bool has_value = k + 1 < argc;
        if (arg == "--tiny")
            small = true;
        else if (arg == "--cases" && has_value)
            names = split_list(argv[++k]);
        else if (arg == "--threads" && has_value) {
            thread_counts.clear();
            for (const auto& s : split_list(argv[++k]))
                thread_counts.push_back(s == "auto" ? 0 : std::atoi(s.c_str())); // 0: tuned
        } else if (arg == "--reorder" && has_value) {
            reorders.clear();
            for (const auto& s : split_list(argv[++k]))
                reorders.push_back(std::atoi(s.c_str()));
        } else if (arg == "--precision" && has_value)
            precisions = split_list(argv[++k]);
        else if (arg == "--steps" && has_value)
            steps = std::atoi(argv[++k]);
        else if (arg == "--rounds" && has_value)
            rounds = std::max(1, std::atoi(argv[++k]));
        else if (arg == "--load" && has_value)
            load = std::max(0, std::atoi(argv[++k]));
        else if (arg == "--scenes" && has_value)
            scenes = argv[++k];
        else if (arg == "--csv" && has_value) {
            csv = std::fopen(argv[++k], "w");
            if (!csv)
                return 2;
        } else
            return usage();
    }
    std::vector<FlowCase> cases;
    for (const auto& name : names) {
        const auto known = all_cases();
        const auto found = std::find_if(known.begin(), known.end(),
                                        [&](const FlowCase& c) { return c.name == name; });
        if (found == known.end())
            return usage();
        cases.push_back(small ? tiny(*found) : *found);
        if (steps > 0)
            cases.back().steps = steps;
    }
    if (small)
        rounds = 1;
    std::vector<Config> configs;
    for (const auto& p : precisions)
        for (int r : reorders)
            for (int t : thread_counts)
                configs.push_back({p, t, r});

    const std::string header = fmt::format(
        "{}, {} logical CPUs, compiler {}, single-precision passes {}, double-precision passes "
        "{}; OMP_WAIT_POLICY {}, "
        "GOMP_SPINCOUNT {}; competing busy processes: {}; load average at start {}",
        cpu_model(), std::thread::hardware_concurrency(), __VERSION__,
        fmt::format("{} ({})", simd_variant(), simd_instructions()), vector_clone_variant(),
        environment("OMP_WAIT_POLICY"), environment("GOMP_SPINCOUNT"), load, load_average());
    fmt::print("flow benchmark: {}\n{} rounds, configurations interleaved; adaptive steps as "
               "`sphclip run` takes them; particles are fluid particles (walls extra)\n",
               header, rounds);
    if (csv) {
        fmt::print(csv, "# sphclip_bench_flow, {}\n", header);
        fmt::print(csv, "case,dimension,particles,precision,threads,reorder_every,steps,rounds,"
                        "particle_steps_per_s,min,max,ns_per_particle_step,neighbours_per_particle,"
                        "ns_per_pair,same_hash_as_1_thread,"
                        "stages_ns_per_particle_step\n");
    }
    const CompetingLoad competing(load);
    for (const auto& c : cases) {
        const bool three = c.name.find("_3d") != std::string::npos;
        if (three)
            run_case<3>(c, scenes, configs, rounds, csv);
        else
            run_case<2>(c, scenes, configs, rounds, csv);
    }
    fmt::print("\nload average at the end {}\n", load_average());
    if (csv) {
        fmt::print(csv, "# load average at the end {}\n", load_average());
        std::fclose(csv);
    }
    return 0;
}
