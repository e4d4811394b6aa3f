#pragma once
// The scene: everything about one clip. A plain struct with a default and a
// unit on every field (the defaults are the built-in scene, a 2D dam break
// after Martin & Moyce 1952), filled from a JSON scene file and overridden by
// `--set KEY=VALUE`. Vectors hold 3 components; a 2D scene uses the first 2.

#include "scene/render_choices.hpp"
#include "sph/boundaries/obstacle_keys.hpp"
#include "sph/boundaries/paddle_keys.hpp"
#include "sph/effects/artificial_viscosity.hpp"
#include "sph/effects/gravity.hpp"
#include "sph/effects/surface_tension.hpp"
#include "sph/effects/viscosity_keys.hpp"
#include "sph/effects/xsph.hpp"
#include "sph/hydrostatic_start.hpp"
#include "sph/params.hpp"
#include "sph/scene_key.hpp"
#include "sph/solvers/solver_keys.hpp"
#include "sph/sources/emitter_keys.hpp"

#include <array>
#include <filesystem>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

namespace sph {

struct FluidBlock {
    Vec3 min{0, 0, 0};               // m
    Vec3 max{0.05715, 0.1143, 0.15}; // m
    Vec3 velocity{0, 0, 0};          // m/s, initial velocity of its particles
};

// x264's presets (render.video_preset), fastest first: faster ones make
// larger files at the same quality.
enum class VideoPreset {
    ultrafast,
    superfast,
    veryfast,
    faster,
    fast,
    medium,
    slow,
    slower,
    veryslow
};
inline const std::vector<std::string>& video_preset_names() {
    static const std::vector<std::string> names{"ultrafast", "superfast", "veryfast",
                                                "faster",    "fast",      "medium",
                                                "slow",      "slower",    "veryslow"};
    return names;
}
// The name libx264 knows it by.
inline const std::string& video_preset_name(VideoPreset preset) {
    return video_preset_names()[static_cast<std::size_t>(preset)];
}

struct Scene {
    std::string name = "default";        // the file's stem; the output folder's default name
    std::string file = "built-in scene"; // where it came from, for messages

    int dimension = 2;     // 2 or 3
    double duration = 1.0; // s of simulated time
    double fps = 30;       // frames per simulated second

    struct Domain {
        Vec3 min{0, 0, 0};         // m
        Vec3 max{0.4, 0.25, 0.15}; // m
    } domain;

    struct Fluid {
        double spacing = 0.05715 / 40; // m, lattice spacing of the blocks
        std::vector<FluidBlock> blocks{FluidBlock{}};
        std::optional<double> smoothing_ratio;  // h / spacing; default 2.5 (2D), 2.2 (3D)
        std::optional<double> smoothing_length; // m, overrides the ratio
        std::optional<double> mass;             // kg; default: rest density on the lattice
        FluidStart start = FluidStart::rest;    // rest | hydrostatic (sph/hydrostatic_start.hpp)
    } fluid;

    struct Material {
        double rest_density = 1000; // kg/m^3
        double bulk_modulus = 2e5;  // Pa
        double viscosity = 1.0;     // Pa.s (damps the seed model; docs/model.md)
    } material;

    SolverSettings solver; // sph/solvers/solver_keys.hpp

    // The per-step checks (sph/watchdog.hpp).
    struct Watchdog {
        int retries = WatchdogSettings{}.retries; // halvings of a failed step before exit 3
        double max_density_ratio = WatchdogSettings{}.max_density_ratio; // collapse: rho / rho0
        double max_displacement = WatchdogSettings{}.max_displacement;   // support radii per step
        std::optional<double> max_speed; // m/s; default from the scene (Derived::max_speed)
    } watchdog;

    // Each present key is an effect in the step; an absent one costs nothing.
    // The settings and keys of each are declared in its file (sph/effects/).
    struct Effects {
        // On unless an `effects` object leaves it out.
        std::optional<GravitySettings> gravity = GravitySettings{};
        // From effects.viscosity or, without it, a material.viscosity above 0
        // with the solver's default model.
        std::optional<ViscositySettings> viscosity;
        // effects.artificial_viscosity, or solver.artificial_viscosity for wcsph.
        std::optional<ArtificialViscositySettings> artificial_viscosity;
        std::optional<XsphSettings> xsph;
        std::optional<SurfaceTensionSettings> surface_tension;
        std::vector<SceneObstacle> obstacles; // static solids; none by default
        std::vector<SceneEmitter> emitters;   // fluid sources; none by default
        std::vector<ScenePaddle> paddles;     // moving boxes; none by default
    } effects;

    struct Render {
        std::array<int, 2> size{1280, 720}; // px
        ColourField colour = ColourField::velocity;
        std::optional<ColourMap> colour_map;        // none (auto): the field's own
        std::optional<std::array<double, 2>> range; // field values at the map's ends
        SphereDrawing spheres = SphereDrawing::impostor;
        FluidStyle style = FluidStyle::spheres;
        bool cull_buried = true; // 3D: skip particles no camera can see
        int video_quality = 20;  // x264 constant quality (CRF), 0 best - 51
        VideoPreset video_preset = VideoPreset::veryfast; // x264 speed/size trade-off
        std::optional<GlBackend> backend;                 // none (auto): EGL, then OSMesa
        std::optional<std::string> title;                 // above the scene; none by default
        std::optional<std::string> caption; // {time} {frame} {steps}; default time and frame
        std::optional<std::string> font;    // a font file; default DejaVu Sans
        bool shadows = false;               // 3D: the key light's soft shadows
        bool ambient_occlusion = false;     // 3D: screen-space ambient occlusion
        bool floor = true;                  // 3D: a floor under the domain
        bool tank = true;                   // 3D: the domain's walls as faint glass
        Background background = Background::light;
        // Over MPI ranks; none (auto): by depth from a measured particle count.
        std::optional<MpiComposite> mpi_composite;
        struct Camera {
            // What the default camera frames: the domain, the fluid where it
            // starts (blocks and emitters), or the fluid's bounds as they move.
            CameraFit fit = CameraFit::domain;
            std::optional<Vec3> position; // m (3D); default from `fit`
            std::optional<Vec3> target;   // m (3D); default from `fit`
            std::optional<Vec3> up;       // 3D; default +y
            double fov = 40;              // degrees, vertical (3D)
            std::optional<Vec3> centre;   // m (2D): the view's centre; default from `fit`
            std::optional<double> height; // m (2D): the height of plane in view
            // 3D: the scene rectangle's width / height; default from the camera
            std::optional<double> aspect;
            // A camera path: keyframes in time (render/camera.hpp interpolates).
            struct Keyframe {
                double time = 0;                      // s
                std::optional<Vec3> position, target; // m (3D)
                std::optional<Vec3> up;               // 3D; default +y
                std::optional<double> fov;            // degrees (3D); default `fov`
                std::optional<Vec3> centre;           // m (2D)
                std::optional<double> height;         // m (2D)
            };
            std::vector<Keyframe> path;
            // Round the fit's target over the clip (3D).
            struct Orbit {
                double turns = 1;               // over the clip; negative: clockwise from above
                double elevation_deg = 20;      // above the horizontal
                double start_deg = 30;          // azimuth at t = 0, from +z towards +x
                std::optional<double> distance; // m; default the fit's, the same all round
            };
            std::optional<Orbit> orbit;
        } camera;
        struct Surface {         // style surface (render/surface/)
            double voxel = 0.5;  // x spacing, the level set's (2D: grid's) cell
            double radius = 1.0; // x spacing, each particle's sphere (2D: half the kernel's)
            int smoothing = 2;   // smoothing passes
        } surface;
    } render;

    struct Output {
        std::optional<std::string> name; // folder under out/; default the scene's name
    } output;
};

// Values derived from the scene (docs/scenes.md, "Derived quantities").
struct Derived {
    double h = 0;    // m, support radius
    double mass = 0; // kg
    double dt = 0;   // s, the fixed step, or the adaptive rule's first step
    bool fixed_dt = false;
    KernelKind kernel = KernelKind::seed;              // solver.kernel resolved
    WallModel walls = WallModel::reflect;              // solver.walls resolved
    Precision precision = Precision::double_precision; // solver.precision resolved
    PairTerms pair_terms = PairTerms::both_sides;      // solver.pair_terms resolved
    double sound_speed = 0;                            // m/s, sqrt(K / rho0)
    double max_speed = 0;                              // m/s, watchdog.max_speed resolved
    // Lattice sites of the blocks; the sites in or beside obstacles are left
    // empty at setup (make_initial_state).
    std::size_t particles = 0;
};

// One documented scene key, collected while reading (for `sphclip keys`).
struct KeyDoc {
    std::string path, type, unit, default_value, description;
};

// `--set KEY=VALUE` overrides, in command-line order.
struct Override {
    std::string key, value;
};

// Reads a scene file (JSON, comments allowed) and applies the overrides.
// Throws InputError naming the file and field on any bad input.
Scene load_scene(const std::filesystem::path& file, const std::vector<Override>& overrides);
// The built-in default scene with the overrides applied.
Scene default_scene(const std::vector<Override>& overrides);
// Parses scene text (the part of load_scene after reading the file).
Scene parse_scene(const std::string& text, const std::string& file_label,
                  const std::vector<Override>& overrides);

// out/<output.name>, by default out/<scene name>: where `sphclip run` writes
// without --out. Throws InputError when the name would lead outside out/.
std::filesystem::path output_folder(const Scene& scene);

// Every key with type, unit, default and meaning.
std::vector<KeyDoc> scene_keys();

Derived derive(const Scene& scene);
// Why solver.precision "single" cannot run this scene (the resolved kernel
// given); empty when it can. "auto" is single exactly when this is empty.
std::string single_precision_obstacle(const Scene& scene, KernelKind kernel);
// The solver.dt / cfl / dt_min / dt_max keys as the core's settings.
TimeStepSettings time_step_settings(const Scene& scene);
// The scene as resolved: all fields, derived values filled in; feeding it back
// to parse_scene gives the same scene.
nlohmann::json to_json(const Scene& scene);

} // namespace sph
