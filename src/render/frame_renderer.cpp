#include "render/frame_renderer.hpp"

#include "render/camera.hpp"
#include "render/frame_end.hpp"
#include "render/gl_resources.hpp"
#include "render/light_rig.hpp"
#include "render/overlay.hpp"
#include "render/particle_batch.hpp"
#include "render/scenery.hpp"
#include "render/sphere_pass.hpp"
#include "render/surface/frame_surface.hpp"
#include "render/surface/surface_pass.hpp"
#include "sph/wall_clock.hpp"

#include <algorithm>
#include <chrono>

namespace sph {

// Everything that lives on the GPU or is reused from frame to frame, in the
// order the frame uses it. The fluid is drawn as spheres or, with
// render.style = surface, as the mesh of its surface.
struct FrameRenderer::Parts {
    gl::RenderTarget target;
    gl::Texture colour_map;
    OutlineRule outline_rule;
    ParticleBatch batch;
    SpherePass spheres;
    FlatPainter painter;
    // render.style = surface: the frame's surface and the mesh pass, made
    // only for that style.
    std::shared_ptr<FrameSurface> surfaces;
    std::unique_ptr<SurfacePass> surface;
    Scenery scenery;
    Overlay overlay;
    // The overlay's room measured, the scene's place around it.
    FrameLayout layout;
    // Each frame's camera, fitted into the scene's place.
    CameraRig rig;
    CameraPose pose;
    // The key light, its shadows and the ambient occlusion.
    LightRig light;

    Parts(const RenderSettings& s, std::shared_ptr<FrameSurface> shared)
        : target(s.width, s.height, s.samples),
          colour_map(gl::make_colour_map_texture(s.colour_map)), outline_rule(s),
          batch(s, outline_groups), spheres(s),
          surfaces(s.style != FluidStyle::surface ? nullptr
                   : shared                       ? std::move(shared)
                            : std::make_shared<FrameSurface>(s.field, s.spacing, s.surface)),
          surface(s.style == FluidStyle::surface ? std::make_unique<SurfacePass>(s) : nullptr),
          scenery(s), overlay(s), layout(layout_for(s, overlay.room())),
          rig(s, layout.scene.width / std::max(1.0, layout.scene.height)),
          light(s, scenery.reach()) {}
};

FrameRenderer::FrameRenderer(const RenderSettings& settings, std::shared_ptr<FrameSurface> surface)
    : settings_(settings), parts_(std::make_unique<Parts>(settings_, std::move(surface))) {
    gl::check_gl("renderer set-up");
}

FrameRenderer::~FrameRenderer() = default;

const std::string& FrameRenderer::font_warning() const {
    return parts_->overlay.font_warning();
}

const CameraPose& FrameRenderer::last_pose() const {
    return parts_->pose;
}

double FrameRenderer::scene_aspect() const {
    return parts_->layout.aspect;
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
    PartClock parts(time_parts_, timings_.part_seconds);
    // The scene's camera, fitted into the room the overlay leaves.
    p.pose = p.rig.pose(frame);
    const Camera camera = make_camera(settings_, p.pose, p.layout);
    // Which particles to draw, and on which outline (for a surface, the
    // batch's counts of particles outside the colour range still warn).
    p.batch.fill(frame, camera, p.outline_rule);
    timings_.fill_seconds = seconds_since(start);
    parts.mark(FramePart::fill);
    // The surface from the particles, on the CPU (once a frame, whoever
    // asks first).
    const Surface* surface = nullptr;
    if (p.surface) {
        const auto surface_start = Clock::now();
        surface = &p.surfaces->of(frame);
        timings_.surface_seconds = seconds_since(surface_start);
        timings_.surface_vertices = surface->mesh.vertices();
        parts.mark(FramePart::surface);
    }

    // The key light, and the depth of what casts its shadows: the fluid
    // (its spheres or its surface) and the solids.
    if (p.surface)
        p.surface->upload(surface->mesh, camera);
    else
        p.spheres.upload(p.batch);
    parts.mark(FramePart::upload);
    const Lighting lighting = p.light.light(camera, {[&](const Camera& light) {
                                                         if (p.surface)
                                                             p.surface->draw_depth(light);
                                                         else
                                                             p.spheres.draw_depth(p.batch, light);
                                                     },
                                                     [&](const Camera& light) {
                                                         p.scenery.draw_depth(light);
                                                     }});
    p.spheres.set_lighting(lighting);
    p.scenery.set_lighting(lighting);
    parts.mark(FramePart::shadow_map);

    // The backdrop; the fluid and colour bar share the colour map.
    p.target.begin();
    p.overlay.backdrop().draw();
    gl::bind_colour_map(p.colour_map);
    parts.mark(FramePart::backdrop);
    // The floor, then the fluid, depth-tested with itself and with the
    // solids; their creases darkened.
    p.scenery.draw_floor(camera);
    parts.mark(FramePart::floor);
    if (p.surface)
        p.surface->draw(camera);
    else
        p.spheres.draw(p.batch, camera);
    parts.mark(FramePart::fluid);
    p.scenery.draw_solids(camera);
    parts.mark(FramePart::solids);
    p.light.occlude(p.target, camera);
    parts.mark(FramePart::occlusion);
    // The glass, the solids' lines and the overlay, then the pixels read
    // back.
    return finish_frame(p.scenery, p.overlay, p.painter, p.target, camera, frame, p.layout, start,
                        timings_, parts);
}

} // namespace sph
