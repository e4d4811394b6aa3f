#include "render_variants.hpp"

#include "render/camera.hpp"
#include "render/frame_end.hpp"
#include "render/gl_resources.hpp"
#include "render/light_rig.hpp"
#include "render/overlay.hpp"
#include "render/particle_batch.hpp"
#include "render/scenery.hpp"
#include "render/sphere_pass.hpp"
#include "sph/wall_clock.hpp"

#include <algorithm>
#include <array>
#include <bench_shaders.hpp>
#include <chrono>
#include <cstdint>
#include <embedded_shaders.hpp>
#include <span>
#include <string>
#include <vector>

namespace sph {

namespace {

// The renderer's groups (square_group, triangle_group), then the flat discs.
constexpr std::size_t flat_group = 2, groups = 3;

// Orders the instances (x, y, z, scalar each) by their depth keys, nearest
// first, in 4096 classes of equal depth range: a counting sort, one pass to
// count and one to place, stable within a class.
void sort_by_depth(std::span<float> instances, const std::vector<float>& keys,
                   std::vector<float>& scratch, std::vector<std::uint32_t>& starts) {
    const std::size_t n = instances.size() / 4;
    if (n < 2)
        return;
    constexpr std::size_t classes = 4096;
    const auto [lo, hi] = std::minmax_element(keys.begin(), keys.begin() + std::ptrdiff_t(n));
    const float scale = *hi > *lo ? float(classes - 1) / (*hi - *lo) : 0.f;
    auto class_of = [&](std::size_t i) {
        return std::size_t((keys[i] - *lo) * scale);
    };
    starts.assign(classes + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
        ++starts[class_of(i) + 1];
    for (std::size_t c = 0; c < classes; ++c)
        starts[c + 1] += starts[c];
    scratch.resize(n * 4);
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t to = starts[class_of(i)]++;
        std::copy_n(instances.begin() + std::ptrdiff_t(i * 4), 4,
                    scratch.begin() + std::ptrdiff_t(to * 4));
    }
    std::copy_n(scratch.begin(), n * 4, instances.begin());
}

} // namespace

// The renderer's parts (FrameRenderer::Parts) and the variants' own.
struct VariantRenderer::Parts {
    gl::RenderTarget target;
    gl::Texture colour_map;
    OutlineRule outline_rule;
    ParticleBatch batch;
    SpherePass spheres;
    FlatPainter painter;
    Scenery scenery;
    Overlay overlay;
    FrameLayout layout;
    // Flat discs: their program, and for points one vertex per instance.
    gl::Program disc_program;
    gl::VertexArray point_vao;
    // Sorting: each group's depth keys, filled as the batch is, and scratch.
    std::array<std::vector<float>, groups> depth_keys;
    std::array<std::size_t, groups> keyed{};
    std::vector<float> sorted;
    std::vector<std::uint32_t> class_starts;
    LightRig light;

    Parts(const RenderSettings& s, const DrawVariant& v)
        : target(s.width, s.height, s.samples),
          colour_map(gl::make_colour_map_texture(s.colour_map)), outline_rule(s), batch(s, groups),
          spheres(s, v.conservative_depth ? "#define CONSERVATIVE_DEPTH\n" : ""), scenery(s),
          overlay(s), layout(layout_frame(s.width, s.height, overlay.room(), scene_aspect(s))),
          light(s, scenery.reach()) {
        if (v.flat_below_px > 0) {
            const std::string defines = v.flat_as_points ? "#define POINTS\n" : "";
            disc_program = gl::link_program(shaders::sphere_disc_vert, shaders::sphere_disc_frag,
                                            defines + std::string(shaders::lighting));
        }
        if (v.flat_as_points) {
            point_vao = gl::VertexArray::generate();
            glBindVertexArray(point_vao.id());
            bind_instance_attributes(spheres.instance_buffer(), 0);
            glBindVertexArray(0);
        }
    }
};

VariantRenderer::VariantRenderer(const RenderSettings& settings, const DrawVariant& variant)
    : settings_(settings), variant_(variant), parts_(std::make_unique<Parts>(settings_, variant_)) {
    gl::check_gl("variant renderer set-up");
}

VariantRenderer::~VariantRenderer() = default;

std::size_t VariantRenderer::last_drawn() const {
    return parts_->batch.drawn();
}
std::size_t VariantRenderer::last_flat() const {
    return parts_->batch.count(flat_group);
}
std::size_t VariantRenderer::last_outside_view() const {
    return parts_->batch.outside_view();
}

Image VariantRenderer::render(const Snapshot& frame) {
    Parts& p = *parts_;
    const DrawVariant& v = variant_;
    const auto start = Clock::now();
    const Camera camera = make_camera(settings_, fixed_pose(settings_), p.layout);
    const bool may_flat = settings_.spheres == SphereDrawing::impostor && v.flat_below_px > 0;
    if (v.sort_front_to_back)
        for (std::size_t g = 0; g < groups; ++g) {
            p.depth_keys[g].resize(frame.size());
            p.keyed[g] = 0;
        }
    // As the renderer's rule, with flat discs below theirs; the batch keeps
    // each group in the snapshot's order, so the keys follow it.
    p.batch.fill(frame, camera, [&](const SphereImage& image) {
        std::size_t group = p.outline_rule(image);
        if (may_flat && image.narrower_than(v.flat_below_px) &&
            (!v.flat_as_points || image.wholly_in_view()))
            group = flat_group;
        if (v.sort_front_to_back)
            p.depth_keys[group][p.keyed[group]++] = float(image.clip_depth());
        return group;
    });
    if (v.sort_front_to_back)
        for (std::size_t g = 0; g < groups; ++g)
            sort_by_depth(p.batch.instances(g), p.depth_keys[g], p.sorted, p.class_starts);
    timings_.fill_seconds = seconds_since(start);

    // Lit, shadowed and occluded as the renderer's frames are.
    p.spheres.upload(p.batch);
    const Lighting lighting =
        p.light.light(camera, {[&](const Camera& light) { p.spheres.draw_depth(p.batch, light); },
                               [&](const Camera& light) {
                                   p.scenery.draw_depth(light);
                               }});
    p.spheres.set_lighting(lighting);
    p.scenery.set_lighting(lighting);
    p.target.begin();
    p.overlay.backdrop().draw();
    gl::bind_colour_map(p.colour_map);
    p.scenery.draw_floor(camera);
    p.spheres.draw(p.batch, camera);
    if (const std::size_t flat = p.batch.count(flat_group); flat > 0) {
        const GLuint program = p.disc_program.id();
        p.spheres.set_uniforms(program, camera);
        glUniform1f(glGetUniformLocation(program, "u_viewport_height"), float(settings_.height));
        if (v.flat_as_points) {
            glEnable(GL_PROGRAM_POINT_SIZE);
            glBindVertexArray(p.point_vao.id());
            glDrawArrays(GL_POINTS, GLint(p.spheres.first(flat_group)), GLsizei(flat));
        } else {
            p.spheres.draw_outlines(Outline::triangle, p.spheres.first(flat_group), flat);
        }
    }
    p.scenery.draw_solids(camera);
    p.light.occlude(p.target, camera);
    PartClock parts(false, timings_.part_seconds);
    return finish_frame(p.scenery, p.overlay, p.painter, p.target, camera, frame, p.layout, start,
                        timings_, parts);
}

} // namespace sph
