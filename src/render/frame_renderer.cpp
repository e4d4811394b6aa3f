#include "render/frame_renderer.hpp"

#include "render/ambient_occlusion.hpp"
#include "render/camera.hpp"
#include "render/frame_end.hpp"
#include "render/gl_resources.hpp"
#include "render/overlay.hpp"
#include "render/palette.hpp"
#include "render/particle_batch.hpp"
#include "render/scenery.hpp"
#include "render/shadow_pass.hpp"
#include "render/sphere_pass.hpp"

#include <chrono>
#include <optional>

namespace sph {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

} // namespace

// Everything that lives on the GPU or is reused from frame to frame, in the
// order the frame uses it. A second way of drawing the fluid (a surface
// mesh) would be a batch and a pass of its own beside the spheres'.
struct FrameRenderer::Parts {
    gl::RenderTarget target;
    gl::Texture colour_map;
    OutlineRule outline_rule;
    ParticleBatch batch;
    SpherePass spheres;
    FlatPainter painter;
    Scenery scenery;
    Overlay overlay;
    // The overlay's room measured, the scene's place around it.
    FrameLayout layout;
    // Light and depth (3D, each where the settings ask for it).
    std::optional<ShadowMap> shadow_map;
    std::optional<AmbientOcclusion> occlusion;

    explicit Parts(const RenderSettings& s)
        : target(s.width, s.height, s.samples),
          colour_map(gl::make_colour_map_texture(s.colour_map)), outline_rule(s),
          batch(s, outline_groups), spheres(s), scenery(s), overlay(s),
          layout(layout_frame(s.width, s.height, overlay.room(), scene_aspect(s))) {
        if (s.dimension == 3 && s.shadows)
            shadow_map.emplace(shadow_map_size(scenery.reach(), s.radius));
        // Occluders count within four sphere radii: the creases between
        // neighbours and the first layer behind the surface.
        if (s.dimension == 3 && s.ambient_occlusion)
            occlusion.emplace(s.width, s.height, 4 * s.radius);
    }
};

FrameRenderer::FrameRenderer(const RenderSettings& settings)
    : settings_(settings), parts_(std::make_unique<Parts>(settings_)) {
    gl::check_gl("renderer set-up");
}

FrameRenderer::~FrameRenderer() = default;

const std::string& FrameRenderer::font_warning() const {
    return parts_->overlay.font_warning();
}

std::size_t FrameRenderer::last_drawn() const {
    return parts_->batch.drawn();
}
std::size_t FrameRenderer::last_outside_view() const {
    return parts_->batch.outside_view();
}

std::size_t FrameRenderer::last_below_range() const {
    return parts_->batch.below_range();
}
std::size_t FrameRenderer::last_above_range() const {
    return parts_->batch.above_range();
}

Image FrameRenderer::render(const Snapshot& frame) {
    Parts& p = *parts_;
    const auto start = Clock::now();
    // The scene's camera, fitted into the room the overlay leaves.
    const Camera camera = make_camera(settings_, fixed_pose(settings_), p.layout);
    // Which particles to draw, and on which outline.
    p.batch.fill(frame, camera, p.outline_rule);
    timings_.fill_seconds = seconds_since(start);

    // The key light, and the depth of what casts its shadows.
    p.spheres.upload(p.batch);
    Lighting lighting = key_light(camera, settings_.up, palette(settings_.background));
    if (p.shadow_map && !camera.orthographic) {
        p.shadow_map->render(
            camera, p.scenery.reach(), 1.5 * settings_.radius, lighting,
            {[&](const Camera& light) { p.spheres.draw_depth(p.batch, light); },
             [&](const Camera& light) { p.scenery.draw_depth(light); }});
        p.shadow_map->bind();
    }
    p.spheres.set_lighting(lighting);
    p.scenery.set_lighting(lighting);

    // The backdrop; spheres and colour bar share the colour map.
    p.target.begin();
    p.overlay.backdrop().draw();
    gl::bind_colour_map(p.colour_map);
    // The floor, then the spheres, depth-tested with each other and with
    // the solids; their creases darkened.
    p.scenery.draw_floor(camera);
    p.spheres.draw(p.batch, camera);
    p.scenery.draw_solids(camera);
    if (p.occlusion && !camera.orthographic)
        p.occlusion->apply(p.target, camera);
    // The solids and the overlay, then the pixels read back.
    return finish_frame(p.scenery, p.overlay, p.painter, p.target, camera, frame, p.layout, start,
                        timings_);
}

} // namespace sph
