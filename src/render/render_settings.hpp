#pragma once
// What a frame shows and how it is drawn, filled from the scene's render
// section: a plain struct with defaults and units (STYLE.md point 10).

#include "render/surface/surface_mesh.hpp"
#include "scene/scene.hpp"

#include <array>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

struct RenderSettings {
    int width = 1280, height = 720; // px
    int dimension = 2;
    ColourField field = ColourField::velocity;
    std::string label = "speed (m/s)";                     // the colour bar's title
    std::string title;                                     // above the scene, left; empty: none
    std::string caption = "t = {time} s    frame {frame}"; // format_caption's pattern; empty: none
    std::string font; // a font file; empty: find_font's default
    ColourMap colour_map = ColourMap::viridis;
    std::array<double, 2> range{0, 1}; // field values at the ends of the map
    // The key that set `range` ("render.range"), or empty when it is the
    // field's default from the scene's physics (default_colour_range).
    std::string range_key;
    // How the fluid is drawn: spheres (one per particle) | surface (a mesh
    // of the free surface reconstructed each frame, render/surface/).
    FluidStyle style = FluidStyle::spheres;
    SurfaceSettings surface; // style surface
    double spacing = 0.002;  // m, the particles' lattice spacing
    SphereDrawing spheres = SphereDrawing::impostor;
    int mesh_subdivisions = 1; // mesh: 80 triangles per sphere
    double radius = 0.001;     // m, drawn sphere radius
    glm::dvec3 domain_min{0}, domain_max{1};
    std::vector<SceneObstacle> obstacles; // drawn solid (2D) or as wire outlines (3D)
    // Drawn as boxes (as box obstacles are) where their motion has them at
    // the frame's time: the motion is known in closed form, so the snapshot
    // need not carry it.
    std::vector<Paddle<3>> paddles;
    glm::dvec3 camera_position{0}, camera_target{0}; // 3D; 2D: the target is the view's centre
    double fov = 40;                                 // degrees, vertical
    // The camera, resolved per frame by CameraRig (render/camera.hpp).
    // camera_fixed: camera_position, camera_target, camera_up and fov (3D),
    // or camera_target and view_height (2D) as they are, with view_height 0
    // the domain. Otherwise the camera is fitted (camera_fit), with
    // target_given, centre_given or view_height > 0 kept as given, or moved
    // along camera_path, or round an orbit.
    bool camera_fixed = true;
    CameraFit camera_fit = CameraFit::domain;
    glm::dvec3 camera_up{0, 1, 0};
    double view_height = 0; // m, 2D
    bool target_given = false, centre_given = false;
    glm::dvec3 fluid_min{0}, fluid_max{0}; // where the fluid starts: blocks and emitters
    struct CameraKeyframe {
        double time = 0;                   // s
        glm::dvec3 position{0}, target{0}; // m; 2D: the target is the centre
        glm::dvec3 up{0, 1, 0};
        double fov = 40, height = 0; // degrees (3D), m (2D)
    };
    std::vector<CameraKeyframe> camera_path; // in increasing time
    struct Orbit {
        double turns = 1, elevation_deg = 20, start_deg = 30; // degrees
        double distance = 0;                                  // m; 0: from the fit
    };
    std::optional<Orbit> orbit;
    double fps = 0, duration = 0; // the clip's; fps 0: a frame's time is its snapshot's
    // 3D: the scene's rectangle takes the aspect of the domain as the default
    // camera sees it, so the colour bar sits beside the tank; false: the
    // room the overlay leaves. make_render_settings sets it for 3D scenes.
    bool frame_to_domain = false;
    // 3D: the scene rectangle's aspect as given (render.camera.aspect); 0:
    // from the camera (layout_for).
    double scene_aspect = 0;
    int samples = 4; // multisampling
    // Skip particles the snapshot marks as buried deep in the fluid (3D).
    bool cull_buried = false;
    // Impostors narrower than this (px) are drawn on one triangle around the
    // sphere's image, wider ones on a square of two: the triangle has 30%
    // more area but half the triangles, and llvmpipe's cost for small spheres
    // is mostly per vertex and triangle, for large ones per fragment
    // (tests/bench/results/render.csv). 0: squares only.
    double triangles_below_px = 12;
    // Skip particles whose sphere lies wholly outside the view: they colour
    // no pixel, so the frame is the same without them.
    // Not with shadows (casts_shadows): a particle outside the view may
    // shadow one inside it.
    bool cull_outside_view = true;
    // Light and depth (docs/rendering.md, "Light and depth"); the first four
    // act in 3D only.
    // Off by default: on llvmpipe each costs more than a plain 10k frame
    // (tests/bench/results/render_light.csv), past the 100 ms goal.
    bool shadows = false;                      // the key light's soft shadows
    bool ambient_occlusion = false;            // screen-space ambient occlusion
    bool floor = true;                         // a floor under the domain
    bool tank = true;                          // the domain's walls as faint glass
    Background background = Background::light; // palette.hpp
    glm::dvec3 up{0, 1, 0};                    // unit, against gravity: the floor's normal
};

// The field's range when the scene sets none, from the scene's physics, the
// same for the whole clip so a colour means the same in every frame
// (docs/rendering.md, "Colour"): speed 0 .. the fastest a particle can get
// by falling from the highest fluid or inlet (plus its initial or inlet
// speed); pressure 0 .. the hydrostatic pressure under the deepest fluid (in
// zero gravity the dynamic pressure of that speed); density rho0 (1 +- d),
// d twice the flow's squared Mach number (v / c)^2 (c the sound speed), at
// least 1%.
std::array<double, 2> default_colour_range(const Scene& scene, ColourField field);

// Whether the key light casts shadows: 3D, render.shadows.
inline bool casts_shadows(const RenderSettings& s) {
    return s.dimension == 3 && s.shadows;
}

// Settings from the scene's render section; ranges the scene leaves open come
// from the scene's physics, so colours mean the same in every frame.
RenderSettings make_render_settings(const Scene& scene);

} // namespace sph
