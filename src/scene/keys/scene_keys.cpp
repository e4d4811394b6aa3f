#include "scene/keys/scene_keys.hpp"

namespace sph {

const KeyTable<Scene>& top_level_keys() {
    static const KeyTable<Scene> keys{
        {.path = "dimension",
         .field = &Scene::dimension,
         .doc = "Spatial dimension: 2 or 3.",
         .min = 2,
         .max = 3},
        {.path = "duration",
         .field = &Scene::duration,
         .unit = "s",
         .doc = "Simulated time of the clip: the run ends there, with a last frame at "
                "that time when it is not a whole number of frames.",
         .bound = Bound::positive},
        {.path = "fps",
         .field = &Scene::fps,
         .unit = "1/s",
         .doc = "Frames per simulated second.",
         .bound = Bound::positive},
    };
    return keys;
}

const KeyTable<Scene::Domain>& domain_keys() {
    using S = Scene::Domain;
    static const KeyTable<S> keys{
        {.path = "min", .field = &S::min, .unit = "m", .doc = "Lower corner of the walls' box."},
        {.path = "max", .field = &S::max, .unit = "m", .doc = "Upper corner of the walls' box."},
    };
    return keys;
}

const KeyTable<Scene::Fluid>& fluid_keys() {
    using S = Scene::Fluid;
    static const KeyTable<S> keys{
        {.path = "spacing",
         .field = &S::spacing,
         .unit = "m",
         .doc = "Lattice spacing of the particles in the fluid blocks.",
         .bound = Bound::positive},
        {.path = "smoothing_ratio",
         .field = &S::smoothing_ratio,
         .doc = "Support radius h as a multiple of the spacing.",
         .bound = Bound::positive,
         .absent = "2.5 (2D), 2.2 (3D)"},
        {.path = "smoothing_length",
         .field = &S::smoothing_length,
         .unit = "m",
         .doc = "Support radius h of the kernels (the seed's interaction radius); overrides the "
                "ratio.",
         .bound = Bound::positive,
         .absent = "ratio x spacing"},
        {.path = "mass",
         .field = &S::mass,
         .unit = "kg",
         .doc = "Mass of each particle; by default the mass that gives a lattice particle "
                "exactly the rest density.",
         .bound = Bound::positive,
         .absent = "rest density on the lattice"},
        {.path = "start",
         .field = enum_field<&S::start>(),
         .doc = "State of the blocks at the start: rest (every particle at the rest density, zero "
                "pressure) or hydrostatic (each block at the pressure of its own weight, as a "
                "column held behind a gate: for seed and wcsph the lattice compressed along "
                "gravity by the equation of state; dfsph's first solve finds that pressure).",
         .choices = {"rest", "hydrostatic"}},
    };
    return keys;
}

const KeyTable<FluidBlock>& block_keys() {
    using S = FluidBlock;
    static const KeyTable<S> keys{
        {.path = "min", .field = &S::min, .unit = "m", .doc = "Lower corner of the block."},
        {.path = "max", .field = &S::max, .unit = "m", .doc = "Upper corner of the block."},
        {.path = "velocity",
         .field = &S::velocity,
         .unit = "m/s",
         .doc = "Initial velocity of the block's particles."},
    };
    return keys;
}

const KeyTable<Scene::Material>& material_keys() {
    using S = Scene::Material;
    static const KeyTable<S> keys{
        {.path = "rest_density",
         .field = &S::rest_density,
         .unit = "kg/m^3",
         .doc = "Rest density rho0.",
         .bound = Bound::positive},
        {.path = "bulk_modulus",
         .field = &S::bulk_modulus,
         .unit = "Pa",
         .doc = "Bulk modulus K of the linear law p = K (rho - rho0) / rho0; speed of sound "
                "c = sqrt(K / rho0).",
         .bound = Bound::positive},
        {.path = "viscosity",
         .field = &S::viscosity,
         .unit = "Pa.s",
         .doc = "Dynamic viscosity mu.",
         .bound = Bound::non_negative},
    };
    return keys;
}

const KeyTable<Scene::Watchdog>& watchdog_keys() {
    using S = Scene::Watchdog;
    static const KeyTable<S> keys{
        {.path = "retries",
         .field = &S::retries,
         .doc = "Times a step that fails the watchdog is retried, halved each time, before the "
                "run stops with exit code 3.",
         .min = 0,
         .max = 20},
        {.path = "max_density_ratio",
         .field = &S::max_density_ratio,
         .doc = "Density over rest density above which a step counts as failed (a collapse).",
         .bound = Bound::positive},
        {.path = "max_displacement",
         .field = &S::max_displacement,
         .unit = "h",
         .doc = "Support radii a particle may move in one step before the step counts as failed "
                "(the CFL condition broken).",
         .bound = Bound::positive},
        {.path = "max_speed",
         .field = &S::max_speed,
         .unit = "m/s",
         .doc = "Speed above which a step counts as failed. Default: twice the sum of the sound "
                "speed, the speed of a fall over the whole domain, the fastest initial, emitter "
                "or paddle velocity, and the speed sqrt(2 e) that the compression energy e "
                "stored at the start (most at the densest particle) can release.",
         .bound = Bound::positive,
         .absent = "auto"},
    };
    return keys;
}

} // namespace sph
