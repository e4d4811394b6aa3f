// sphclip_torture: runs the torture suite (every case under tests/stability/,
// every solver) and prints the table of docs/stability.md. The same runs are the
// [stability] tests; this program only reports them.
//   sphclip_torture [--csv FILE] [CASE.json ...]

#include "sph/solvers/solver.hpp"
#include "torture.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <omp.h>

using namespace sph;

int main(int argc, char** argv) {
    std::FILE* csv = nullptr;
    std::vector<std::string> only;
    for (int k = 1; k < argc; ++k) {
        if (std::strcmp(argv[k], "--csv") == 0 && k + 1 < argc) {
            csv = std::fopen(argv[++k], "w");
            if (!csv) {
                fmt::print(stderr, "sphclip_torture: cannot write {}\n", argv[k]);
                return 2;
            }
            fmt::print(csv, "case,solver,passed,steps,retries,dt_min,dt_max,max_density_error_pct,"
                            "max_speed,speed_limit,energy_growth,wall_s\n");
        } else {
            only.emplace_back(argv[k]);
        }
    }
    fmt::print("| case | solver | passed | steps | dt range (s) | max density error | max speed "
               "(limit) | energy growth | retries |\n|---|---|---|---|---|---|---|---|---|\n");
    int failed = 0;
    for (const auto& c : torture::cases()) {
        if (!only.empty() && std::find(only.begin(), only.end(), c.scene) == only.end())
            continue;
        for (const auto& solver : solver_names()) {
            const auto r = torture::run(SPHCLIP_STABILITY_DIR, c, solver);
            failed += !r.passed(c);
            fmt::print("| {} | {} | {} | {} | {:.2g} - {:.2g} | {:.3g}% | {:.3g} ({:.3g}) m/s | {} "
                       "| {} |\n",
                       c.scene.substr(0, c.scene.size() - 5), solver,
                       !r.passed(c)          ? "NO"
                       : !r.stop.empty()     ? "stopped (exit 3)"
                       : !r.warnings.empty() ? "yes (physics checks fail, seed)"
                                             : "yes",
                       r.steps, r.dt_min, r.dt_max, r.max_density_error_pct, r.max_speed,
                       r.speed_limit, c.closed ? fmt::format("{:.2g}", r.energy_growth) : "n/a",
                       r.retries);
            for (const auto& f : r.failures)
                fmt::print(stderr, "  {} / {}: {}\n", c.scene, solver, f);
            for (const auto& f : r.warnings)
                fmt::print(stderr, "  {} / {} (physics): {}\n", c.scene, solver, f);
            if (!r.stop.empty())
                fmt::print(stderr, "  {} / {}: {}\n", c.scene, solver, r.stop);
            if (csv)
                fmt::print(csv, "{},{},{},{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.3f}\n",
                           c.scene, solver, r.passed(c) ? 1 : 0, r.steps, r.retries, r.dt_min,
                           r.dt_max, r.max_density_error_pct, r.max_speed, r.speed_limit,
                           r.energy_growth, r.wall_seconds);
            std::fflush(stdout);
        }
    }
    if (csv)
        std::fclose(csv);
    return failed ? 1 : 0;
}
