#include "sph/solvers/solver_keys.hpp"

#include "sph/neighbours/neighbour_search.hpp"
#include "sph/solvers/solver.hpp"

namespace sph {

const KeyTable<SolverSettings>& solver_keys() {
    using S = SolverSettings;
    static const KeyTable<S> keys{
        {.path = "name",
         .field = enum_field<&S::name>(),
         .doc = "Solver: seed (the report's model), wcsph (Becker & Teschner 2007) or dfsph "
                "(Bender & Koschier 2017).",
         .choices = solver_names()},
        {.path = "kernel",
         .field = auto_enum_field<&S::kernel>(),
         .doc = "Smoothing kernel: seed (poly6 values, spiky gradients), cubic_spline or "
                "wendland_c2; auto: seed for the seed solver, cubic_spline for the others.",
         .choices = {"auto", "seed", "cubic_spline", "wendland_c2"}},
        {.path = "dt",
         .field = &S::dt,
         .unit = "s",
         .doc = "Fixed time step; without it the step adapts (solver.cfl, solver.dt_min, "
                "solver.dt_max).",
         .bound = Bound::positive,
         .absent = "adaptive"},
        {.path = "cfl",
         .field = &S::cfl,
         .doc = "Courant number of the adaptive step: dt <= cfl h / (c + v_max) for seed and "
                "wcsph, dt <= cfl spacing / v_max for dfsph.",
         .bound = Bound::positive},
        {.path = "dt_min",
         .field = &S::dt_min,
         .unit = "s",
         .doc = "Smallest adaptive step.",
         .bound = Bound::positive},
        {.path = "dt_max",
         .field = &S::dt_max,
         .unit = "s",
         .doc = "Largest adaptive step.",
         .bound = Bound::positive},
        {.path = "integrator",
         .field = enum_field<&S::integrator>(),
         .doc = "Time integrator of seed and wcsph: symplectic_euler (first order, the seed's) "
                "or verlet (kick-drift-kick, second order).",
         .choices = {"symplectic_euler", "verlet"}},
        {.path = "walls",
         .field = auto_enum_field<&S::walls>(),
         .doc = "Domain walls: reflect (the seed's) or particles (Akinci et al. 2012 boundary "
                "particles); auto: reflect for seed, particles for the others.",
         .choices = {"auto", "reflect", "particles"}},
        {.path = "wall_pressure",
         .field = enum_field<&S::wall_pressure>(),
         .doc = "Pressure of the boundary particles (wcsph, dfsph): mirror (the fluid particle's "
                "own, p_b = p_i) or hydrostatic (plus the weight of the fluid between them, "
                "p_b = max(p_i + rho_i g . (x_b - x_i), 0) for every wall, Adami et al. 2012), so "
                "that the layers at a floor are not compressed beyond the hydrostatic pressure "
                "and a side wall holds the fluid as fluid would; or "
                "extrapolated (wcsph: Adami et al. 2012's eq. 27 whole, the Shepard average of "
                "the fluid's pressures around the wall particle plus that weight; double "
                "precision).",
         .choices = {"mirror", "hydrostatic", "extrapolated"}},
        {.path = "density_diffusion",
         .field = &S::density_diffusion,
         .doc = "wcsph: delta of delta-SPH's density diffusion (Antuono et al. 2010, with the "
                "renormalised density gradient; 0.1 is the usual value). Above 0 the density is "
                "carried by the continuity equation rather than summed (symplectic Euler only), "
                "in double precision; 0: summed. The other solvers sum their density and ignore "
                "it.",
         .bound = Bound::non_negative},
        {.path = "density",
         .field = enum_field<&S::density>(),
         .doc = "dfsph: the density its solves hold at the rest density: summed (over the "
                "neighbours and wall particles each step) or carried (by the continuity "
                "equation, at the rate the density solve predicts, from the summed one but not "
                "below the rest density: no deficit at a free surface). The other solvers "
                "ignore it (wcsph carries its density with solver.density_diffusion).",
         .choices = {"summed", "carried"}},
        {.path = "artificial_viscosity",
         .field = &S::artificial_viscosity,
         .doc = "Alpha of Monaghan's artificial viscosity (wcsph and dfsph).",
         .bound = Bound::non_negative},
        {.path = "tolerance",
         .field = &S::tolerance,
         .unit = "%",
         .doc = "dfsph: mean density error the density solve stops at.",
         .bound = Bound::positive},
        {.path = "divergence_tolerance",
         .field = &S::divergence_tolerance,
         .unit = "%",
         .doc = "dfsph: mean density change per step the divergence solve stops at.",
         .bound = Bound::positive},
        {.path = "min_iterations",
         .field = &S::min_iterations,
         .doc = "dfsph: fewest iterations of each solve.",
         .min = 0,
         .max = 100000},
        {.path = "max_iterations",
         .field = &S::max_iterations,
         .doc = "dfsph: most iterations of each solve.",
         .min = 1,
         .max = 100000},
        {.path = "warm_start",
         .field = &S::warm_start,
         .doc = "dfsph: start each pressure solve from a part of the last step's pressure, "
                "but at the free surface (particles below the rest density); 1.3-1.7x fewer "
                "iterations on dam breaks and deep tanks."},
        {.path = "warm_start_fraction",
         .field = &S::warm_start_fraction,
         .doc = "dfsph, with warm_start: the part of the last step's density-solve pressure "
                "each density solve starts from. 1 (all of it) saves the most iterations, but "
                "a deep tank's pressure then bounces between zero and twice hydrostatic; "
                "0.5 damps that (the solve rebuilds half each step).",
         .bound = Bound::fraction},
        {.path = "momentum",
         .field = &S::momentum,
         .doc = "dfsph: the heavy-ball term of the solves' iterations (Polyak 1964): each "
                "particle's pressure step adds this times its last one while the two agree in "
                "sign; below 1. 0: plain relaxed Jacobi. 0.5 takes 1.6-1.7x fewer density "
                "iterations on dam breaks and a deep tank, for 6-12% less time in 3D and none "
                "in 2D; the fastest particles then run 15% faster and a tank's pressure is "
                "less exact (2D tank 0.2% -> 1.5% RMS). docs/solvers.md",
         .bound = Bound::non_negative},
        {.path = "neighbour_search",
         .field = enum_field<&S::neighbour_search>(),
         .doc = "Neighbour search.",
         .choices = neighbour_search_names()},
        {.path = "reorder_every",
         .field = &S::reorder_every,
         .doc = "Steps between spatial sorts of the particle arrays by grid cell (Morton order), "
                "which keep neighbours near in memory; 0: never. Changes round-off only. "
                "Without the key, the solver's: 20 for seed and wcsph, 1 for dfsph (whose "
                "neighbour lists cost less to build from arrays in cell order).",
         .min = 0,
         .max = 1000000,
         .absent = "20; dfsph: 1"},
        {.path = "rebalance_above",
         .field = &S::rebalance_above,
         .doc = "Over MPI ranks: between steps, the ranks' ranges of the cell order are cut "
                "again by particle count when the rank owning the most holds more than this "
                "times the mean (besides at every spatial sort); particles then move between "
                "ranks. Changes nothing in the results. From 1 to 1000.",
         .bound = Bound::positive},
        {.path = "precision",
         .field = auto_enum_field<&S::precision>(),
         .doc = "Arithmetic of wcsph's density and pressure passes: single (float, a grid cell "
                "at a time, no neighbour lists; 1.3-1.8x faster in 2D, 1.0-1.4x in 3D for "
                "about 27% more memory) or double (neighbour lists); auto: single where it can "
                "run (wcsph with a smooth kernel on the sorted grid, without density "
                "diffusion, extrapolated wall pressure, XSPH or surface tension; in 3D from "
                "2,000 fluid particles at the start) on a processor with 8-float vectors (AVX2 "
                "or wider), else double.",
         .choices = {"auto", "single", "double"}},
        {.path = "pair_terms",
         .field = auto_enum_field<&S::pair_terms>(),
         .doc = "3D wcsph in single precision: each pair of fluid particles in two different "
                "grid cells computed from both sides, or once (Newton's third law: the cell "
                "first along the Morton curve adds the other particle's term to it), the "
                "cells then taken in tiles of 4^3 cells, one colour of 8 at a time, so a small "
                "scene has fewer tiles than threads; auto: once from 10,000 fluid particles at "
                "the start (1.1-1.2x on 2 cores from 11,700 to 97,000). Changes round-off "
                "only.",
         .choices = {"auto", "both_sides", "once"}},
        {.path = "cell_skin",
         .field = &S::cell_skin,
         .doc = "2D wcsph in single precision: its grid cells are made this fraction of the "
                "kernel's support wider, at one step's positions, and serve the steps after "
                "until a particle has moved half that far (a Verlet skin, on cells); made "
                "without it while the fastest particle moves more than half of it a step (a "
                "sound speed near the flow's: no build would be saved). Their build, a sixth "
                "of the step on DualSPHysics's 2D dam break, then runs every few steps, for "
                "a few more candidates in each pass: 1.04-1.12x on the 2D flows. 0: made "
                "every step. Not with moving walls (paddles), which make them every step. "
                "Changes round-off only.",
         .bound = Bound::fraction,
         .absent = "0.05",
         .only_dimension = 2},
    };
    return keys;
}

} // namespace sph
