#pragma once
// The scene's `solver` object: which solver, kernel, integrator, walls and
// neighbour search, and the settings of the time step and the pressure
// solve. Defaults shared with the core's settings structs (params.hpp) are
// taken from them, so each is written once.

#include "sph/neighbours/neighbour_search.hpp"
#include "sph/params.hpp"
#include "sph/scene_key.hpp"

#include <optional>
#include <string>

namespace sph {

struct SolverSettings {
    SolverKind name = SolverKind::seed;        // seed | wcsph | dfsph
    std::optional<KernelKind> kernel;          // none: auto, the solver's default
    std::optional<double> dt;                  // s; fixed step; default adaptive
    double cfl = TimeStepSettings{}.cfl;       // Courant number of the adaptive step
    double dt_min = TimeStepSettings{}.dt_min; // s
    double dt_max = TimeStepSettings{}.dt_max; // s
    Integrator integrator = Integrator::symplectic_euler;
    std::optional<WallModel> walls;                       // none: auto, the solver's default
    double artificial_viscosity = 0.02;                   // alpha (wcsph; see effects)
    double tolerance = PressureSolveSettings{}.tolerance; // % (dfsph)
    double divergence_tolerance = PressureSolveSettings{}.divergence_tolerance; // % per step
    int min_iterations = PressureSolveSettings{}.min_iterations;                // dfsph
    int max_iterations = PressureSolveSettings{}.max_iterations;                // dfsph
    bool warm_start = PressureSolveSettings{}.warm_start;                       // dfsph
    double warm_start_fraction = PressureSolveSettings{}.warm_start_fraction;   // dfsph
    double momentum = PressureSolveSettings{}.momentum;                         // dfsph
    // sorted_grid | hash (the seed's) | all_pairs
    NeighbourSearchKind neighbour_search = NeighbourSearchKind::sorted_grid;
    // Steps between spatial sorts of the particle arrays by cell; 0: never;
    // none: the solver's default (SolverCapabilities::reorder_every).
    std::optional<int> reorder_every;
    double rebalance_above = 1.1;
    // The arithmetic of wcsph's density and pressure passes
    // (sph/single_precision/cell_passes.hpp); none: auto.
    std::optional<Precision> precision;
    // How the 3D single-precision passes take a fluid pair; none: auto.
    std::optional<PairTerms> pair_terms;
    // 2D single-precision passes: how much wider than the support their
    // cells are made, a fraction of it; none: the default (scene_setup).
    std::optional<double> cell_skin;
    // mirror | hydrostatic | extrapolated (sph/params.hpp)
    WallPressure wall_pressure = WallPressure::mirror;
    // wcsph: delta of delta-SPH (Antuono et al. 2010); 0: the density summed.
    double density_diffusion = 0;
    // dfsph: summed | carried (sph/params.hpp)
    DensityModel density = DensityModel::summed;
};

// The keys of `solver`, in the order `sphclip keys` lists them.
const KeyTable<SolverSettings>& solver_keys();

} // namespace sph
