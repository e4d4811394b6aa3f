#pragma once
// Particle batching: which particles of a snapshot are drawn and how, seen
// through the frame's camera. Particles the snapshot marks as buried and
// spheres wholly outside the view are skipped; each of the others becomes an
// instance (x, y, z relative to the camera's origin, and the coloured
// scalar: four floats) in one of the batch's groups, one group per way of
// drawing a sphere, chosen by a rule from the sphere's image (OutlineRule is
// the renderer's). The batch holds spheres only: a surface mesh of the fluid
// would be a batch of its own, drawn beside this one.

#include "render/camera.hpp"
#include "render/render_settings.hpp"
#include "sph/snapshot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <limits>
#include <span>
#include <vector>

namespace sph {

// The scalar a particle is coloured by.
enum class ParticleField { speed, density, pressure };

// What turns a position into the size and place of its sphere's image, for
// one frame's camera.
struct ImageMeasures {
    glm::dvec4 w_row, z_row; // clip-space w and z of a position: rows of the clip matrix
    double width_times_w;    // the sphere's image width (px) times its w
    double cull_margin;      // m: a sphere this far outside a plane colours no pixel
};

// One sphere as a rule sees it when choosing how to draw it.
class SphereImage {
  public:
    SphereImage(const glm::dvec4& position, double inside, const ImageMeasures& measures)
        : position_(position), inside_(inside), measures_(measures) {}
    // In front of the eye, and its image narrower than `px` pixels.
    bool narrower_than(double px) const {
        const double w = glm::dot(measures_.w_row, position_);
        return w > 0 && measures_.width_times_w < px * w;
    }
    // Its whole image inside the view's sides (known only when culling).
    bool wholly_in_view() const { return inside_ > measures_.cull_margin; }
    // Its centre's clip-space z, for ordering by depth.
    double clip_depth() const { return glm::dot(measures_.z_row, position_); }

  private:
    const glm::dvec4& position_; // relative to the camera's origin, w = 1
    double inside_;              // distance inside the nearest side plane
    const ImageMeasures& measures_;
};

class ParticleBatch {
  public:
    // Groups of instances, `groups` ways of drawing; the culling and the
    // field from the settings.
    ParticleBatch(const RenderSettings& settings, std::size_t groups);

    // Refills the groups from `frame`'s particles [first, last), in the
    // snapshot's order within each group: group_of(const SphereImage&) gives
    // each drawn particle's group. By default every particle; over MPI ranks
    // with depth compositing, the rank's own (depth_composite.hpp).
    template <class GroupOf>
    void fill(const Snapshot& frame, const Camera& camera, GroupOf group_of, std::size_t first = 0,
              std::size_t last = std::numeric_limits<std::size_t>::max());

    std::size_t groups() const { return counts_.size(); }
    std::size_t count(std::size_t group) const { return counts_[group]; }
    // The group's instances, four floats each.
    std::span<const float> instances(std::size_t group) const {
        return {instances_[group].data(), counts_[group] * 4};
    }
    std::span<float> instances(std::size_t group) {
        return {instances_[group].data(), counts_[group] * 4};
    }
    // Particles drawn, in all groups, and those skipped as outside the view.
    std::size_t drawn() const;
    std::size_t outside_view() const { return outside_view_; }
    // Drawn particles whose scalar lies below or above the colour range
    // (drawn in the map's end colours).
    std::size_t below_range() const { return below_range_; }
    std::size_t above_range() const { return above_range_; }

  private:
    ImageMeasures measures(const Camera& camera) const;

    ParticleField field_;
    double radius_;
    bool cull_buried_, cull_outside_view_;
    double cull_margin_;
    std::array<double, 2> range_;
    // Scratch reused from frame to frame, each group sized for every particle.
    std::vector<std::vector<float>> instances_;
    std::vector<std::size_t> counts_;
    std::size_t outside_view_ = 0;
    std::size_t below_range_ = 0, above_range_ = 0;
};

// The renderer's rule (RenderSettings::triangles_below_px): impostors whose
// image is narrower than the threshold on one triangle, the others on a
// square; meshes are all group 0.
enum SphereGroup : std::size_t { square_group = 0, triangle_group = 1 };
constexpr std::size_t outline_groups = 2;

struct OutlineRule {
    bool triangles = false; // impostors and a threshold > 0
    double triangles_below_px = 0;
    explicit OutlineRule(const RenderSettings& settings);
    std::size_t operator()(const SphereImage& image) const {
        return triangles && image.narrower_than(triangles_below_px) ? triangle_group : square_group;
    }
};

template <class GroupOf>
void ParticleBatch::fill(const Snapshot& frame, const Camera& camera, GroupOf group_of,
                         std::size_t first, std::size_t last) {
    const std::size_t n = frame.size();
    for (std::vector<float>& group : instances_)
        group.resize(n * 4);
    std::fill(counts_.begin(), counts_.end(), std::size_t(0));
    outside_view_ = 0;
    below_range_ = above_range_ = 0;
    const std::array<glm::dvec4, 6> planes = view_planes(camera);
    const ImageMeasures m = measures(camera);
    const bool cull_buried = cull_buried_ && frame.buried.size() == n;
    const int dim = frame.dimension;
    // The field is chosen once, not per particle.
    const bool speed = field_ == ParticleField::speed;
    const std::vector<double>& field =
        field_ == ParticleField::density ? frame.density : frame.pressure;
    for (std::size_t i = first; i < std::min(n, last); ++i) {
        if (cull_buried && frame.buried[i])
            continue;
        glm::dvec4 p(0, 0, 0, 1);
        for (int a = 0; a < dim; ++a)
            p[a] = frame.position[i * dim + a] - camera.origin[a];
        // Distance inside the nearest side plane (left, right, bottom, top).
        double inside = std::numeric_limits<double>::lowest();
        if (cull_outside_view_) {
            inside = std::numeric_limits<double>::max();
            bool outside_a_plane = false;
            for (std::size_t k = 0; k < planes.size(); ++k) {
                const double distance = glm::dot(planes[k], p);
                outside_a_plane = outside_a_plane || distance < -m.cull_margin;
                if (k < 4)
                    inside = std::min(inside, distance);
            }
            if (outside_a_plane) {
                ++outside_view_;
                continue;
            }
        }
        double scalar = 0;
        if (speed) {
            for (int a = 0; a < dim; ++a)
                scalar += frame.velocity[i * dim + a] * frame.velocity[i * dim + a];
            scalar = std::sqrt(scalar);
        } else {
            scalar = field[i];
        }
        below_range_ += scalar < range_[0];
        above_range_ += scalar > range_[1];
        const std::size_t group = group_of(SphereImage(p, inside, m));
        float* out = instances_[group].data() + 4 * counts_[group]++;
        for (int a = 0; a < 3; ++a)
            out[a] = float(p[a]);
        out[3] = float(scalar);
    }
}

} // namespace sph
