#include "sph/boundaries/obstacles.hpp"

#include "sph/assert.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

namespace sph {

template <int D>
Real Obstacle<D>::signed_distance(const Vec<D>& x) const {
    if (shape == ObstacleShape::sphere)
        return std::sqrt(squared_length<D>(x - centre)) - radius;
    if constexpr (D == 3)
        if (shape == ObstacleShape::mesh)
            return mesh->signed_distance(x);
    SPHCLIP_ASSERT(shape == ObstacleShape::box);
    // Box: minus the distance to the nearest face inside, the distance to the
    // box outside. From the faces themselves, not centre and half-size, so a
    // point on a face is at 0 exactly.
    Vec<D> q;
    for (int a = 0; a < D; ++a)
        q[a] = std::max(box.min[a] - x[a], x[a] - box.max[a]);
    Real deepest = q[0];
    for (int a = 1; a < D; ++a)
        deepest = std::max(deepest, q[a]);
    const Vec<D> outside = glm::max(q, Vec<D>(0));
    return std::sqrt(squared_length<D>(outside)) + std::min(deepest, Real(0));
}

template <int D>
bool Obstacle<D>::nearer_than(const Vec<D>& x, Real d) const {
    if constexpr (D == 3)
        if (shape == ObstacleShape::mesh) {
            // The distance to the bounding box is a lower bound of the distance
            // to the mesh: most points never reach the triangles.
            const Box<3>& b = mesh->bounds();
            const Vec<3> gap = glm::max(glm::max(b.min - x, x - b.max), Vec<3>(0));
            const Real outside = std::sqrt(squared_length<3>(gap));
            if (outside > 0 && outside >= d)
                return false;
        }
    return signed_distance(x) < d;
}

namespace {

// Volume of a ball (area of a disc in 2D) of radius r.
template <int D>
Real ball_volume(Real r) {
    return D == 2 ? std::numbers::pi_v<Real> * r * r
                  : Real(4) / 3 * std::numbers::pi_v<Real> * r * r * r;
}

// The box's own lattice, stretched to fit it: n_a = round(size / s) sites per
// axis, at min + (k + 1/2) size / n_a, so every face lies half a (local)
// spacing beyond the outer layer, as each domain wall lies half a spacing
// beyond its first layer. A box whose sides are whole multiples of the
// spacing, on the fluid's lattice, continues that lattice exactly. Only the
// sites fewer than `layers` from a face are kept.
template <int D>
void sample_box(const Box<D>& box, Real spacing, std::int64_t layers, Real volume_scale,
                BoundarySamples<D>& out) {
    glm::vec<D, std::int64_t, glm::defaultp> count;
    Vec<D> step;
    Real volume = volume_scale;
    for (int a = 0; a < D; ++a) {
        const Real size = box.max[a] - box.min[a];
        count[a] = std::max<std::int64_t>(1, std::llround(size / spacing));
        step[a] = size / Real(count[a]);
        volume *= step[a];
    }
    auto depth = [&](int a, std::int64_t k) {
        return std::min(k, count[a] - 1 - k);
    };
    auto add = [&](const glm::vec<D, std::int64_t, glm::defaultp>& k) {
        Vec<D> x;
        for (int a = 0; a < D; ++a)
            x[a] = box.min[a] + (Real(k[a]) + Real(0.5)) * step[a];
        out.positions.push_back(x);
        out.volumes.push_back(volume);
    };
    // A row along x whose other coordinates are deep inside keeps only its
    // ends: the interior is skipped, not visited.
    auto add_row = [&](glm::vec<D, std::int64_t, glm::defaultp> k, bool shell_row) {
        for (k[0] = 0; k[0] < count[0]; ++k[0]) {
            if (!shell_row && k[0] == layers && count[0] - layers > layers)
                k[0] = count[0] - layers;
            if (shell_row || depth(0, k[0]) < layers)
                add(k);
        }
    };
    if constexpr (D == 2) {
        for (std::int64_t j = 0; j < count[1]; ++j)
            add_row({0, j}, depth(1, j) < layers);
    } else {
        for (std::int64_t k = 0; k < count[2]; ++k)
            for (std::int64_t j = 0; j < count[1]; ++j)
                add_row({0, j, k}, depth(1, j) < layers || depth(2, k) < layers);
    }
}

// Concentric layers one spacing thick, from the surface inwards: layer l
// spans radii R - (l + 1) s .. R - l s and is sampled on its mid radius with
// about one point per spacing of circumference (2D: evenly on the circle,
// every other layer turned by half a step; 3D: a Fibonacci sphere, evenly
// spread without poles). Each point stands for an equal share of the layer's
// volume. Where a layer would reach the centre, one point at the centre
// stands for the core that is left.
template <int D>
void sample_sphere(const Vec<D>& centre, Real radius, Real spacing, std::int64_t layers,
                   Real volume_scale, BoundarySamples<D>& out) {
    constexpr Real pi = std::numbers::pi_v<Real>;
    const Real golden_angle = pi * (3 - std::sqrt(Real(5)));
    for (std::int64_t l = 0; l < layers; ++l) {
        const Real outer = radius - Real(l) * spacing;
        const Real mid = outer - Real(0.5) * spacing;
        if (mid < Real(0.5) * spacing) {
            out.positions.push_back(centre);
            out.volumes.push_back(volume_scale * ball_volume<D>(std::max(outer, Real(0))));
            return;
        }
        const Real around =
            D == 2 ? 2 * pi * mid / spacing : 4 * pi * mid * mid / (spacing * spacing);
        const auto n = std::max<std::int64_t>(1, std::llround(around));
        const Real volume =
            volume_scale * (ball_volume<D>(outer) - ball_volume<D>(outer - spacing)) / Real(n);
        for (std::int64_t k = 0; k < n; ++k) {
            Vec<D> direction;
            if constexpr (D == 2) {
                const Real angle = 2 * pi * (Real(k) + Real(0.5) * Real(l % 2)) / Real(n);
                direction = {std::cos(angle), std::sin(angle)};
            } else {
                const Real z = 1 - (2 * Real(k) + 1) / Real(n);
                const Real ring = std::sqrt(std::max(Real(0), 1 - z * z));
                const Real angle = golden_angle * Real(k) + Real(l);
                direction = {ring * std::cos(angle), ring * std::sin(angle), z};
            }
            out.positions.push_back(centre + mid * direction);
            out.volumes.push_back(volume);
        }
    }
}

// A closed mesh: the lattice of its bounding box, stretched to fit it as a
// box's is, n_a = round(size / s) sites per axis; the sites inside the solid
// and less than `layers` local spacings (the largest axis') from its surface
// are kept. A cube therefore gets exactly a box's samples. The signed
// distance changes by at most the distance moved (it is 1-Lipschitz), so
// along a row the sites that are certainly outside, or deeper than the
// shell, are stepped over without a query: the cost follows the surface,
// not the volume.
void sample_mesh(const TriangleMesh& mesh, Real spacing, std::int64_t layers, Real volume_scale,
                 BoundarySamples<3>& out) {
    const Box<3>& bounds = mesh.bounds();
    glm::vec<3, std::int64_t, glm::defaultp> count;
    Vec<3> step;
    Real volume = volume_scale, largest = 0;
    for (int a = 0; a < 3; ++a) {
        const Real size = bounds.max[a] - bounds.min[a];
        count[a] = std::max<std::int64_t>(1, std::llround(size / spacing));
        step[a] = size / Real(count[a]);
        volume *= step[a];
        largest = std::max(largest, step[a]);
    }
    const Real depth = Real(layers) * largest;
    // Rows along x, each kept in order; joined in row order, so the result
    // does not depend on the thread count.
    const std::int64_t rows = count[1] * count[2];
    std::vector<std::vector<Vec<3>>> kept(static_cast<std::size_t>(rows));
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t row = 0; row < rows; ++row) {
        Vec<3> x;
        x[1] = bounds.min[1] + (Real(row % count[1]) + Real(0.5)) * step[1];
        x[2] = bounds.min[2] + (Real(row / count[1]) + Real(0.5)) * step[2];
        std::vector<Vec<3>>& own = kept[static_cast<std::size_t>(row)];
        for (std::int64_t k = 0; k < count[0];) {
            x[0] = bounds.min[0] + (Real(k) + Real(0.5)) * step[0];
            const Real d = mesh.signed_distance(x);
            if (d < 0 && d > -depth)
                own.push_back(x);
            // Sites nearer than `certain` along the row are outside (d > 0)
            // or deeper than the shell; a hair less for rounding.
            const Real certain = d >= 0 ? d : -d - depth;
            k += 1 + std::max<std::int64_t>(
                         0, static_cast<std::int64_t>(certain / step[0] * (1 - 1e-9)));
        }
    }
    for (const auto& row : kept)
        for (const Vec<3>& x : row) {
            out.positions.push_back(x);
            out.volumes.push_back(volume);
        }
}

} // namespace

template <int D>
BoundarySamples<D> sample_obstacles(std::span<const Obstacle<D>> obstacles, Real spacing, Real h,
                                    Real lattice_volume) {
    // As deep as the domain walls (BoundaryParticles::box_walls).
    const auto layers = static_cast<std::int64_t>(std::ceil(h / spacing));
    const Real volume_scale = lattice_volume / std::pow(spacing, D);
    BoundarySamples<D> all;
    for (std::size_t i = 0; i < obstacles.size(); ++i) {
        const Obstacle<D>& o = obstacles[i];
        BoundarySamples<D> own;
        if (o.shape == ObstacleShape::box)
            sample_box(o.box, spacing, layers, volume_scale, own);
        else if (o.shape == ObstacleShape::sphere)
            sample_sphere(o.centre, o.radius, spacing, layers, volume_scale, own);
        else if constexpr (D == 3)
            sample_mesh(*o.mesh, spacing, layers, volume_scale, own);
        for (std::size_t b = 0; b < own.positions.size(); ++b) {
            const bool inside_another =
                std::any_of(obstacles.begin(), obstacles.end(), [&](const Obstacle<D>& other) {
                    return &other != &o && other.nearer_than(own.positions[b], 0);
                });
            if (!inside_another) {
                all.positions.push_back(own.positions[b]);
                all.volumes.push_back(own.volumes[b]);
            }
        }
    }
    return all;
}

template <int D>
bool blocked_by_obstacle(std::span<const Obstacle<D>> obstacles, const Vec<D>& x, Real spacing) {
    // The tolerance keeps a site exactly half a spacing away (a lattice that
    // continues the obstacle's) despite rounding.
    const Real clearance = (Real(0.5) - Real(1e-6)) * spacing;
    return std::any_of(obstacles.begin(), obstacles.end(),
                       [&](const Obstacle<D>& o) { return o.nearer_than(x, clearance); });
}

namespace {

// Puts x, found inside o, back on o's nearest surface; returns the outward
// normal there.
template <int D>
Vec<D> put_on_surface(const Obstacle<D>& o, Vec<D>& x) {
    Vec<D> normal(0);
    if constexpr (D == 3)
        if (o.shape == ObstacleShape::mesh) {
            // Out to the closest point, along the direction to it (the
            // distance's gradient: the face's normal on a face).
            const TriangleMesh::Nearest near = o.mesh->nearest(x);
            const Real depth = -near.distance;
            normal = depth > 0 ? (near.point - x) / depth : near.normal;
            x = near.point;
            // Rounding can leave it a hair inside: out by a few ulps more.
            const Box<3>& b = o.mesh->bounds();
            const Real scale = glm::length(b.max - b.min) + glm::length(near.point);
            for (Real hair = 1e-15 * scale; o.signed_distance(x) < 0; hair *= 2)
                x = near.point + hair * normal;
            return normal;
        }
    if (o.shape == ObstacleShape::sphere) {
        const Real r = std::sqrt(squared_length<D>(x - o.centre));
        normal[D - 1] = 1; // the centre itself: straight up
        if (r > 0)
            normal = (x - o.centre) / r;
        x = o.centre + o.radius * normal;
        // Rounding can leave it a hair inside: out by a few ulps more.
        const Real scale = o.radius + std::sqrt(squared_length<D>(o.centre));
        for (Real hair = 1e-15 * scale; o.signed_distance(x) < 0; hair *= 2)
            x = o.centre + (o.radius + hair) * normal;
        return normal;
    }
    return o.box.put_on_nearest_face(x); // the face nearest inside
}

} // namespace

template <int D>
std::size_t push_out_of_obstacles(std::span<const Obstacle<D>> obstacles, State<D>& state) {
    if (obstacles.empty())
        return 0;
    const std::size_t n = state.size();
    std::size_t pushed = 0;
#pragma omp parallel for schedule(static) reduction(+ : pushed)
    for (std::size_t i = 0; i < n; ++i) {
        Vec<D>& x = state.position[i];
        for (const Obstacle<D>& o : obstacles) {
            if (!o.nearer_than(x, 0))
                continue;
            const Vec<D> normal = put_on_surface(o, x);
            Vec<D>& v = state.velocity[i];
            const Real inward = glm::dot(v, normal);
            if (inward < 0)
                v -= 2 * inward * normal;
            ++pushed;
        }
    }
    return pushed;
}

template struct Obstacle<2>;
template struct Obstacle<3>;
template BoundarySamples<2> sample_obstacles<2>(std::span<const Obstacle<2>>, Real, Real, Real);
template BoundarySamples<3> sample_obstacles<3>(std::span<const Obstacle<3>>, Real, Real, Real);
template bool blocked_by_obstacle<2>(std::span<const Obstacle<2>>, const Vec<2>&, Real);
template bool blocked_by_obstacle<3>(std::span<const Obstacle<3>>, const Vec<3>&, Real);
template std::size_t push_out_of_obstacles<2>(std::span<const Obstacle<2>>, State<2>&);
template std::size_t push_out_of_obstacles<3>(std::span<const Obstacle<3>>, State<3>&);

} // namespace sph
