#include "render/frame_renderer.hpp"

#include "render/camera.hpp"
#include "render/depth_composite.hpp"
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
#include <span>

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
    // Over MPI ranks with depth compositing: this rank's spheres, and on
    // rank 0 the other ranks' layers (depth_composite.hpp).
    std::unique_ptr<RankLayer> layer;
    std::unique_ptr<LayerImport> import;
    std::vector<FlatLayer> layers;

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
    return composited_ ? std::size_t(counts_[0]) : parts_->batch.drawn();
}
std::size_t FrameRenderer::last_outside_view() const {
    return composited_ ? std::size_t(counts_[1]) : parts_->batch.outside_view();
}

std::size_t FrameRenderer::last_below_range() const {
    return composited_ ? std::size_t(counts_[2]) : parts_->batch.below_range();
}
std::size_t FrameRenderer::last_above_range() const {
    return composited_ ? std::size_t(counts_[3]) : parts_->batch.above_range();
}

void FrameRenderer::share_over_ranks(RankCompositing* ranks) {
    ranks_ = ranks;
    if (!ranks_)
        return;
    if (settings_.style != FluidStyle::spheres || settings_.spheres != SphereDrawing::impostor)
        throw std::logic_error("depth compositing draws impostor spheres only");
    Parts& p = *parts_;
    p.layer = std::make_unique<RankLayer>(settings_.width, settings_.height, settings_.samples);
    if (ranks_->rank() == 0)
        p.import =
            std::make_unique<LayerImport>(settings_.width, settings_.height, settings_.samples);
    gl::check_gl("depth compositing set-up");
}

Image FrameRenderer::render(const Snapshot& frame) {
    composited_ = ranks_ && ranks_->by_depth(frame.total_particles());
    if (composited_)
        return render_composited(frame);
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

    // The backdrop and the floor, then the fluid, depth-tested with itself
    // and with the solids; their creases darkened.
    draw_behind_fluid(camera, parts);
    if (p.surface)
        p.surface->draw(camera);
    else
        p.spheres.draw(p.batch, camera);
    parts.mark(FramePart::fluid);
    return draw_after_fluid(camera, frame, start, parts);
}

void FrameRenderer::draw_behind_fluid(const Camera& camera, PartClock& parts) {
    Parts& p = *parts_;
    // The backdrop; the fluid and colour bar share the colour map.
    p.target.begin();
    p.overlay.backdrop().draw();
    gl::bind_colour_map(p.colour_map);
    parts.mark(FramePart::backdrop);
    p.scenery.draw_floor(camera);
    parts.mark(FramePart::floor);
}

Image FrameRenderer::draw_after_fluid(const Camera& camera, const Snapshot& frame,
                                      std::chrono::steady_clock::time_point start,
                                      PartClock& parts) {
    Parts& p = *parts_;
    p.scenery.draw_solids(camera);
    parts.mark(FramePart::solids);
    p.light.occlude(p.target, camera);
    parts.mark(FramePart::occlusion);
    // The glass, the solids' lines and the overlay, then the pixels read
    // back.
    return finish_frame(p.scenery, p.overlay, p.painter, p.target, camera, frame, p.layout, start,
                        timings_, parts);
}

// Each rank draws the spheres it owns into its layer, lit by the shadow
// map of every rank's casters; rank 0 writes the layers into its frame, in
// the one-process frame's drawing order, and draws the rest once
// (depth_composite.hpp).
Image FrameRenderer::render_composited(const Snapshot& frame) {
    Parts& p = *parts_;
    const auto start = Clock::now();
    PartClock parts(time_parts_, timings_.part_seconds);
    const bool leader = ranks_->rank() == 0;
    // The frame's camera, fitted by rank 0, which alone holds every
    // particle; each rank draws its own, the first of its snapshot.
    if (leader)
        p.pose = p.rig.pose(frame);
    ranks_->from_leader(std::as_writable_bytes(std::span(&p.pose, 1)));
    const Camera camera = make_camera(settings_, p.pose, p.layout);
    p.batch.fill(frame, camera, p.outline_rule, 0, std::min(frame.owned, frame.size()));
    counts_ = {p.batch.drawn(), p.batch.outside_view(), p.batch.below_range(),
               p.batch.above_range()};
    ranks_->sum_on_leader(counts_);
    timings_.fill_seconds = seconds_since(start);
    parts.mark(FramePart::fill);
    p.spheres.upload(p.batch);
    parts.mark(FramePart::upload);
    // The shadow map of every rank's spheres (and the solids, drawn by
    // every rank: the minimum is the same).
    p.light.combine_shadows(
        [&](std::span<std::uint32_t> depths) { ranks_->min_over_ranks(depths); });
    const Lighting lighting =
        p.light.light(camera, {[&](const Camera& light) { p.spheres.draw_depth(p.batch, light); },
                               [&](const Camera& light) {
                                   p.scenery.draw_depth(light);
                               }});
    p.light.combine_shadows(nullptr);
    p.spheres.set_lighting(lighting);
    p.scenery.set_lighting(lighting);
    parts.mark(FramePart::shadow_map);

    // This rank's spheres, alone.
    const auto composite_start = Clock::now();
    p.layer->begin();
    gl::bind_colour_map(p.colour_map);
    p.spheres.draw_layer(p.batch, camera);
    p.layer->flatten();
    if (!leader) {
        p.layer->read(ranks_->layer_to_send());
        ranks_->send_layer();
        parts.mark(FramePart::fluid);
        timings_.draw_seconds = seconds_since(start);
        composite_seconds_ = seconds_since(composite_start);
        return Image(0, 0);
    }
    // Rank 0: the backdrop and the floor, then every rank's spheres.
    draw_behind_fluid(camera, parts);
    p.layers.assign(std::size_t(ranks_->ranks()), FlatLayer{});
    p.layers[0] = p.layer->flat();
    const std::size_t samples = std::size_t(settings_.width) * std::size_t(settings_.height) *
                                std::size_t(settings_.samples);
    ranks_->receive_layers(samples, [&](int rank, const RankLayerPixels& layer) {
        p.layers[std::size_t(rank)] = p.import->upload(std::size_t(rank) - 1, layer);
    });
    glBindFramebuffer(GL_FRAMEBUFFER, p.target.framebuffer());
    p.import->draw(p.layers, 0);
    p.import->draw(p.layers, triangle_group_bit);
    gl::bind_colour_map(p.colour_map);
    composite_seconds_ = seconds_since(composite_start);
    parts.mark(FramePart::fluid);
    return draw_after_fluid(camera, frame, start, parts);
}

} // namespace sph
