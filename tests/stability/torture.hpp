#pragma once
// The torture suite (docs/stability.md): hard scenes under tests/stability/,
// each run with every solver and checked against invariants after every frame.
// The Catch2 tests assert on the results; sphclip_torture prints them as the
// table of docs/stability.md.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sph::torture {

// What a case expects beyond the invariants every case is held to.
struct Case {
    std::string scene; // file name in tests/stability/
    // Total energy (kinetic + potential + compression) must not grow: false
    // for a case that takes energy in from outside.
    bool closed = true;
    // > 0: the maximum speed over the second half of the run must stay below
    // this (m/s): the case is a fluid at rest.
    double rest_speed = 0;
    // Solvers whose model cannot simulate the case: the watchdog must stop
    // them cleanly (exit 3) before any invariant breaks. The seed may stop
    // cleanly in any case (see Result::passed).
    std::vector<std::string> stops = {};
    // What the stop's message must say, for the solvers in `stops` and
    // `may_stop`.
    std::string stop_reason = {};
    // Solvers at the edge of what their model can follow: they pass if they
    // run the case with every check met, or if the watchdog stops them
    // cleanly with `stop_reason`; which one happens is chaotic.
    std::vector<std::string> may_stop = {};
};

// Every case, in the order of docs/stability.md's table.
const std::vector<Case>& cases();

struct Result {
    std::string scene, solver;
    // Hard invariants broken: a non-finite value (an unexpected stop), a
    // particle lost or outside the domain.
    std::vector<std::string> failures;
    // Physics checks broken: speed over the scene's limit, energy growth, a
    // tank at rest moving. Asserted for every solver but the seed, whose model
    // (poly6 density with spiky forces, negative pressures) is kept as the
    // report wrote it and does not conserve energy; for it they are reported.
    std::vector<std::string> warnings;
    std::string stop; // the watchdog's message, if it stopped the run
    std::uint64_t steps = 0, retries = 0;
    double dt_min = 0, dt_max = 0;         // s
    double max_density_error_pct = 0;      // over all frames
    double max_speed = 0, speed_limit = 0; // m/s
    double energy_growth = 0;              // max (E(t) - E(0)) / energy scale
    double wall_seconds = 0;
    // No invariant broken, and stopped exactly when the case expects it.
    bool passed(const Case& c) const;
};

// Runs `c` from `folder` with solver.name = solver.
Result run(const std::filesystem::path& folder, const Case& c, const std::string& solver);

} // namespace sph::torture
