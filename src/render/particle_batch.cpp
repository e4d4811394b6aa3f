#include "render/particle_batch.hpp"

#include <numeric>

namespace sph {

ParticleBatch::ParticleBatch(const RenderSettings& s, std::size_t groups)
    : field_(s.field == ColourField::velocity  ? ParticleField::speed
             : s.field == ColourField::density ? ParticleField::density
                                               : ParticleField::pressure),
      radius_(s.radius), cull_buried_(s.cull_buried),
      cull_outside_view_(s.cull_outside_view && !casts_shadows(s)),
      // A sphere whose every point is at least a little outside one plane
      // colours no pixel: the impostor's fragments all lie within its
      // silhouette, the mesh within the sphere. The margin covers the GPU's
      // float round-off.
      cull_margin_(1.01 * s.radius + 1e-6 * glm::length(s.domain_max - s.domain_min)),
      range_{std::min(s.range[0], s.range[1]), std::max(s.range[0], s.range[1])},
      instances_(groups), counts_(groups, 0) {}

ImageMeasures ParticleBatch::measures(const Camera& camera) const {
    const glm::dmat4 clip = camera.clip_from_world();
    auto row = [&clip](int r) {
        return glm::dvec4(clip[0][r], clip[1][r], clip[2][r], clip[3][r]);
    };
    return {.w_row = row(3),
            .z_row = row(2),
            .width_times_w = radius_ * camera.pixels_per_radius(),
            .cull_margin = cull_margin_};
}

std::size_t ParticleBatch::drawn() const {
    return std::accumulate(counts_.begin(), counts_.end(), std::size_t(0));
}

OutlineRule::OutlineRule(const RenderSettings& s)
    : triangles(s.spheres == SphereDrawing::impostor && s.triangles_below_px > 0),
      triangles_below_px(s.triangles_below_px) {}

} // namespace sph
