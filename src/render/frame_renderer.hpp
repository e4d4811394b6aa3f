#pragma once
// Draws one frame of particles into an image, in the current GL context:
// instanced lit spheres coloured through a colour map, the domain box, a
// colour bar with its range and unit, and a caption. It sees only the
// Snapshot, never the simulation.

#include "io/image.hpp"
#include "io/scene.hpp"
#include "sph/snapshot.hpp"

#include <array>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace sph {

struct RenderSettings {
    int width = 1280, height = 720; // px
    int dimension = 2;
    std::string field = "velocity";    // velocity | density | pressure
    std::string label = "speed (m/s)"; // the colour bar's title
    std::string colour_map = "viridis";
    std::array<double, 2> range{0, 1}; // field values at the ends of the map
    std::string spheres = "impostor";  // impostor | mesh
    int mesh_subdivisions = 1;         // mesh: 80 triangles per sphere
    double radius = 0.001;             // m, drawn sphere radius
    glm::dvec3 domain_min{0}, domain_max{1};
    std::vector<SceneObstacle> obstacles; // drawn solid (2D) or as wire outlines (3D)
    // Drawn as boxes (as box obstacles are) where their motion has them at
    // the frame's time: the motion is known in closed form, so the snapshot
    // need not carry it.
    std::vector<Paddle<3>> paddles;
    glm::dvec3 camera_position{0}, camera_target{0}; // 3D
    double fov = 40;                                 // degrees, vertical
    int samples = 4;                                 // multisampling
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
    bool cull_outside_view = true;
    // Impostors whose image is narrower than this (px) are drawn as flat,
    // lit discs facing the eye at the sphere's front: no ray cast and no
    // depth written, so llvmpipe can test depth before shading. 0: never.
    double flat_below_px = 0;
    // Flat discs as point sprites, one vertex each, not instanced quads.
    bool flat_as_points = false;
    // Draw the spheres roughly front to back (by a coarse depth key), so the
    // depth test rejects the hidden ones' fragments.
    bool sort_front_to_back = false;
    // Declare the impostors' depth `depth_greater` (ARB_conservative_depth),
    // drawing each quad at its sphere's front. Measured in the benchmark.
    bool conservative_depth = false;
};

// Settings from the scene's render section; ranges the scene leaves open come
// from the scene's physics, so colours mean the same in every frame.
RenderSettings make_render_settings(const Scene& scene);

struct FrameTimings {
    double fill_seconds = 0;     // culling and filling the instances (part of draw_seconds)
    double draw_seconds = 0;     // submitting and finishing the draw
    double readback_seconds = 0; // resolving and reading the pixels
};

class FrameRenderer {
  public:
    // Needs a current GL 4.5 context; throws std::runtime_error on GL errors.
    explicit FrameRenderer(const RenderSettings& settings);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    Image render(const Snapshot& frame);
    const FrameTimings& last_timings() const { return timings_; }
    // Particles drawn in the last frame (buried ones are skipped), those of
    // them drawn as flat discs, and those skipped as outside the view.
    std::size_t last_drawn() const { return drawn_; }
    std::size_t last_flat() const { return flat_; }
    std::size_t last_outside_view() const { return outside_view_; }
    const RenderSettings& settings() const { return settings_; }

  private:
    struct Gl;
    RenderSettings settings_;
    std::unique_ptr<Gl> gl_;
    FrameTimings timings_;
    std::size_t drawn_ = 0, flat_ = 0, outside_view_ = 0;
};

} // namespace sph
