#pragma once
// Fixed parameters of one simulation, derived once from the scene and passed as
// `const Params&` to every stage. Changing quantities live in State.

#include "sph/boundaries/obstacles.hpp"
#include "sph/boundaries/paddles.hpp"
#include "sph/kernels.hpp"
#include "sph/vec.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace sph {

enum class Integrator { symplectic_euler, verlet };

// The pressure a wall particle takes from the fluid particle beside it
// (solver.wall_pressure): mirror, p_b = p_i; hydrostatic, the fluid's
// hydrostatic pressure continued into the wall,
// p_b = max(p_i + rho_i g . (x_b - x_i), 0) (Adami et al. 2012, eq. 27's
// hydrostatic term, pair by pair: higher below the particle, lower above
// it, never below zero, so a wall never pulls the fluid onto it; both sides
// matter beside a side wall, docs/validation.md); extrapolated (wcsph), Adami et al. 2012's
// whole eq. 27: a Shepard average of the fluid's pressures around the wall
// particle plus the weight between (sph/wall_pressure.hpp).
enum class WallPressure { mirror, hydrostatic, extrapolated };

// The density dfsph's solves hold at rho0 (solver.density): summed over
// the neighbours and walls each step (Akinci et al. 2012, eq. 6), or carried
// by the continuity equation from step to step (the rate the density solve
// predicts with), which has no deficit at a free surface (docs/validation.md,
// "The 3D tank at rest").
enum class DensityModel { summed, carried };

// The solvers (solver.name), in the order of solver_names().
enum class SolverKind { seed, wcsph, dfsph };

// The arithmetic of wcsph's density and pressure passes: float over grid
// cells (sph/single_precision/cell_passes.hpp) or double over neighbour lists.
enum class Precision { single, double_precision };

// How wcsph's 3D single-precision passes take a pair of fluid particles in
// two different cells (solver.pair_terms): from both sides, or once, by
// the cell first along the Morton curve, the other particle's term its
// reaction (sph/single_precision/cell_passes.hpp).
enum class PairTerms { both_sides, once };

// How the walls of the domain act on the fluid.
enum class WallModel {
    reflect,  // the seed's: put back inside and reflect the velocity
    particles // boundary particles (Akinci et al. 2012) that take part in density and pressure
};

// Adaptive time step (time_step.hpp); a fixed step when `fixed` is set.
struct TimeStepSettings {
    bool fixed = false;
    Real dt = 0;        // s, the fixed step
    Real cfl = 0.4;     // fraction of a length scale crossed per step
    Real dt_min = 1e-7; // s
    Real dt_max = 5e-3; // s
};

// Pressure solve of the incompressible solvers (dfsph).
struct PressureSolveSettings {
    Real tolerance = 0.05;           // %: mean compression (rho - rho0) / rho0 allowed
    Real divergence_tolerance = 0.1; // %: mean dt (D rho / Dt) / rho0 allowed
    int min_iterations = 2;
    int max_iterations = 100;
    bool warm_start = true;         // start from the last step's pressure...
    Real warm_start_fraction = 0.5; // ...times this (the density solve's; dfsph.cpp)
    Real momentum = 0;              // heavy-ball term of the iterations (dfsph.cpp)
};

// The per-step checks and their retries (watchdog.hpp).
struct WatchdogSettings {
    int retries = 4;             // halvings of a failed step before the run stops
    Real max_density_ratio = 10; // rho / rho0 above which the fluid is collapsing
    Real max_displacement = 1;   // support radii a particle may move in one step
    Real max_speed = std::numeric_limits<Real>::infinity(); // m/s: beyond it, garbage
    // max_speed is the scene's default: the simulation adds twice the speed
    // the start's compression can release (Simulation, at its start).
    bool max_speed_adds_start_energy = false;
};

template <int D>
struct Params {
    Real mass = 0;         // kg, of every particle
    Real h = 0;            // m, support radius of the kernels
    Real spacing = 0;      // m, rest distance between particles
    Real rest_density = 0; // kg/m^3
    Real bulk_modulus = 0; // Pa, K in p = K (rho - rho0)
    Box<D> domain;         // m, the walls
    // Static solids inside the domain, made of boundary particles (obstacles.hpp).
    std::vector<Obstacle<D>> obstacles;
    // Boxes that move with a prescribed motion, made of boundary particles (paddles.hpp).
    std::vector<Paddle<D>> paddles;
    KernelKind kernel = KernelKind::seed;
    Integrator integrator = Integrator::symplectic_euler;
    WallModel walls = WallModel::reflect;
    TimeStepSettings time_step;
    PressureSolveSettings pressure_solve;
    WatchdogSettings watchdog;
    // Steps between spatial sorts of the particle arrays (by cell, along the
    // Morton curve), which keep neighbours near in memory; 0: never.
    int reorder_every = 0;
    // Over MPI ranks: owned particles of the fullest rank / the mean above
    // which the ranges are cut again (src/parallel/rank_partition.cpp).
    Real rebalance_above = 1.1;
    Precision precision = Precision::double_precision;
    PairTerms pair_terms = PairTerms::both_sides;
    // 2D single-precision passes: how much wider than h their cells are, a
    // fraction of h (solver.cell_skin); 0: cells made every step.
    Real cell_skin = 0;
    // Gravity that the walls' pressure adds across the fluid-wall distance
    // (WallPressure::hydrostatic); zero: the mirrored pressure.
    Vec<D> wall_gravity{0}; // m/s^2
    // mirror unless the walls are particles and gravity is on.
    WallPressure wall_pressure = WallPressure::mirror;
    // wcsph: delta of delta-SPH's density diffusion (sph/density_diffusion.hpp);
    // above 0 the density is carried by the continuity equation, at 0 it is
    // summed (solver.density_diffusion).
    Real density_diffusion = 0;
    // dfsph: summed or carried (solver.density); the others ignore it.
    DensityModel density_model = DensityModel::summed;

    Real sound_speed() const { return std::sqrt(bulk_modulus / rest_density); }
};

} // namespace sph
