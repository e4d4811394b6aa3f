#include "render/frame_renderer.hpp"

#include "render/camera.hpp"
#include "render/frame_end.hpp"
#include "render/gl_resources.hpp"
#include "render/light_rig.hpp"
#include "render/overlay.hpp"
#include "render/particle_batch.hpp"
#include "render/scenery.hpp"
#include "render/sphere_pass.hpp"

#include <chrono>

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
    // The key light, its shadows and the ambient occlusion.
    LightRig light;

    explicit Parts(const RenderSettings& s)
        : target(s.width, s.height, s.samples),
          colour_map(gl::make_colour_map_texture(s.colour_map)), outline_rule(s),
          batch(s, outline_groups), spheres(s), scenery(s), overlay(s),
          layout(layout_frame(s.width, s.height, overlay.room(), scene_aspect(s))),
          light(s, scenery.reach()) {}
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
    const Lighting lighting =
        p.light.light(camera, {[&](const Camera& light) { p.spheres.draw_depth(p.batch, light); },
                               [&](const Camera& light) {
                                   p.scenery.draw_depth(light);
                               }});
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
    p.light.occlude(p.target, camera);
    // The solids and the overlay, then the pixels read back.
    return finish_frame(p.scenery, p.overlay, p.painter, p.target, camera, frame, p.layout, start,
                        timings_);
}

} // namespace sph
