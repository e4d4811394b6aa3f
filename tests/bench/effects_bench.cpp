// sphclip_bench_effects: what each effect costs. One scene (the built-in 2D
// dam break, wcsph) is stepped with effects added one by one; for each
// configuration it prints the time per step and per particle-step, and what
// the added effect's stage costs over the configuration it adds to (from the
// simulation's stage times; wcsph times its artificial and laminar
// viscosities inside "pressure", so those rows are the growth of the
// pressure stage).
//   sphclip_bench_effects [--quick] [--steps N] [--csv FILE]

#include "scene/scene_setup.hpp"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <omp.h>
#include <string>
#include <vector>

using namespace sph;

namespace {

struct Config {
    std::string label, added_stage;
    std::vector<Override> overrides;
    int base = -1; // the configuration this one adds to, by position (-1: none)
};

} // namespace

int main(int argc, char** argv) {
    int steps = 300;
    bool quick = false;
    std::FILE* csv = nullptr;
    for (int k = 1; k < argc; ++k) {
        if (std::strcmp(argv[k], "--quick") == 0) {
            quick = true;
            steps = 3;
        } else if (std::strcmp(argv[k], "--steps") == 0 && k + 1 < argc) {
            steps = std::atoi(argv[++k]);
        } else if (std::strcmp(argv[k], "--csv") == 0 && k + 1 < argc) {
            csv = std::fopen(argv[++k], "w");
            if (!csv)
                return 2;
        } else {
            fmt::print(stderr, "usage: sphclip_bench_effects [--quick] [--steps N] [--csv FILE]\n");
            return 2;
        }
    }
    const std::string spacing = quick ? "0.005715" : "0.00142875";
    const std::vector<Override> base{{"solver.name", "wcsph"},
                                     {"solver.dt", "1e-4"},
                                     {"fluid.spacing", spacing},
                                     {"material.viscosity", "0"},
                                     {"solver.artificial_viscosity", "0"},
                                     {"effects", "{}"}};
    // Each configuration adds one effect to the one before (the seed's
    // viscosity row swaps Morris's model for the seed's instead).
    const std::string gravity = R"("gravity": [0, -9.81])";
    const std::string artificial = gravity + R"(, "artificial_viscosity": {"alpha": 0.02})";
    const std::string morris = artificial + R"(, "viscosity": {"model": "morris", "mu": 1})";
    const std::string seed = artificial + R"(, "viscosity": {"model": "seed", "mu": 1})";
    const std::string xsph = morris + R"(, "xsph": {"epsilon": 0.5})";
    const std::string tension = xsph + R"(, "surface_tension": {"gamma": 1})";
    const std::string emitter =
        tension +
        R"(, "emitters": [{"min": [0.3, 0.15], "max": [0.306, 0.19], "velocity": [-1, 0]}])";
    auto effects = [](const std::string& list) {
        return std::vector<Override>{{"effects", "{" + list + "}"}};
    };
    const std::vector<Config> configs{
        {"pressure only (no effects, no viscosity)", "", {}},
        {"+ gravity", "gravity", effects(gravity), 0},
        {"+ artificial viscosity (alpha 0.02)", "pressure", effects(artificial), 1},
        {"+ laminar viscosity (Morris, 1 Pa.s)", "pressure", effects(morris), 2},
        {"  (the seed's viscosity instead of Morris's)", "viscosity", effects(seed), 2},
        {"+ XSPH (epsilon 0.5)", "xsph", effects(xsph), 3},
        {"+ surface tension (gamma 1)", "surface_tension", effects(tension), 5},
        {"+ emitter (10 particles / 4 ms)", "emitters", effects(emitter), 6},
    };
    // Per configuration, ns per particle-step of each stage.
    std::vector<std::vector<std::pair<std::string, double>>> stage_costs;
    auto cost_of = [&](int config, std::string_view stage) {
        if (config < 0)
            return 0.0;
        for (const auto& [name, ns] : stage_costs[static_cast<std::size_t>(config)])
            if (name == stage)
                return ns;
        return 0.0;
    };
    fmt::print("effects benchmark: built-in 2D dam break, wcsph, spacing {} m, dt 1e-4 s, {} "
               "steps, {} threads\n\n",
               spacing, steps, omp_get_max_threads());
    fmt::print(
        "| configuration | particles | ms / step | ns / particle-step | added stage's growth, "
        "ns / particle-step |\n|---|---|---|---|---|\n");
    if (csv)
        fmt::print(csv, "configuration,particles,ms_per_step,ns_per_particle_step,added_stage,"
                        "added_ns_per_particle_step\n");
    for (const auto& c : configs) {
        std::vector<Override> o = base;
        o.insert(o.end(), c.overrides.begin(), c.overrides.end());
        auto sim = make_simulation<2>(default_scene(o));
        for (int k = 0; k < (quick ? 1 : 20); ++k) // warm up: lists and arrays sized
            sim.step();
        const auto steps_before = sim.particle_steps();
        const auto stages_before = sim.stage_times().entries();
        const auto start = std::chrono::steady_clock::now();
        for (int k = 0; k < steps; ++k)
            sim.step();
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double particle_steps = double(sim.particle_steps() - steps_before);
        auto& costs = stage_costs.emplace_back();
        for (const auto& e : sim.stage_times().entries()) {
            double before = 0;
            for (const auto& b : stages_before)
                if (b.name == e.name)
                    before = b.seconds;
            costs.emplace_back(std::string(e.name), (e.seconds - before) * 1e9 / particle_steps);
        }
        const int self = static_cast<int>(stage_costs.size()) - 1;
        const double added = cost_of(self, c.added_stage) - cost_of(c.base, c.added_stage);
        const std::string added_text =
            c.added_stage.empty() ? "-" : fmt::format("{:.1f} ({})", added, c.added_stage);
        fmt::print("| {} | {} | {:.3f} | {:.1f} | {} |\n", c.label, sim.state().size(),
                   seconds * 1e3 / steps, seconds * 1e9 / particle_steps, added_text);
        if (csv)
            fmt::print(csv, "\"{}\",{},{:.4f},{:.2f},{},{:.2f}\n", c.label, sim.state().size(),
                       seconds * 1e3 / steps, seconds * 1e9 / particle_steps, c.added_stage,
                       c.added_stage.empty() ? 0.0 : added);
        std::fflush(stdout);
    }
    if (csv)
        std::fclose(csv);
    return 0;
}
