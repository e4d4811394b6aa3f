#include "sph/boundaries/paddles.hpp"

#include "sph/boundaries/obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sph {

template <int D>
Vec<D> Paddle<D>::displacement(Real t) const {
    if (t <= start)
        return Vec<D>(0);
    if (motion == PaddleMotion::linear)
        return (std::min(t, end) - start) * velocity;
    const Real omega = 2 * std::numbers::pi_v<Real> / period;
    return std::sin(omega * (t - start)) * amplitude;
}

template <int D>
Vec<D> Paddle<D>::velocity_at(Real t) const {
    // At `start` itself the motion has begun: a sine starts at full speed.
    if (t < start)
        return Vec<D>(0);
    if (motion == PaddleMotion::linear)
        return t < end ? velocity : Vec<D>(0);
    const Real omega = 2 * std::numbers::pi_v<Real> / period;
    return (omega * std::cos(omega * (t - start))) * amplitude;
}

template <int D>
Real Paddle<D>::peak_speed() const {
    if (motion == PaddleMotion::linear)
        return glm::length(velocity);
    return 2 * std::numbers::pi_v<Real> / period * glm::length(amplitude);
}

template <int D>
Box<D> Paddle<D>::box_at(Real t) const {
    const Vec<D> d = displacement(t);
    return {box.min + d, box.max + d};
}

template <int D>
PaddleSamples<D> sample_paddles(std::span<const Paddle<D>> paddles, Real spacing, Real h,
                                Real lattice_volume) {
    PaddleSamples<D> all;
    for (std::size_t k = 0; k < paddles.size(); ++k) {
        Obstacle<D> box;
        box.shape = ObstacleShape::box;
        box.box = paddles[k].box;
        const BoundarySamples<D> own =
            sample_obstacles<D>(std::span(&box, 1), spacing, h, lattice_volume);
        all.positions.insert(all.positions.end(), own.positions.begin(), own.positions.end());
        all.volumes.insert(all.volumes.end(), own.volumes.begin(), own.volumes.end());
        all.paddle.insert(all.paddle.end(), own.positions.size(), static_cast<std::uint32_t>(k));
    }
    return all;
}

template <int D>
void move_paddles(std::span<const Paddle<D>> paddles, Real t, BoundaryParticles<D>& boundary) {
    const auto rest = boundary.rest_positions();
    const auto owner = boundary.groups();
    const auto x = boundary.moving_positions();
    const auto v = boundary.moving_velocities();
    // Samples come paddle by paddle: one motion evaluated per run of them.
    for (std::size_t k = 0; k < rest.size();) {
        const std::uint32_t paddle = owner[k];
        const Vec<D> d = paddles[paddle].displacement(t);
        const Vec<D> velocity = paddles[paddle].velocity_at(t);
        for (; k < rest.size() && owner[k] == paddle; ++k) {
            x[k] = rest[k] + d;
            v[k] = velocity;
        }
    }
    boundary.refresh_moving_grid();
}

template <int D>
std::size_t push_out_of_paddles(std::span<const Paddle<D>> paddles, Real t, State<D>& state) {
    if (paddles.empty())
        return 0;
    const std::size_t n = state.size();
    std::size_t pushed = 0;
    for (const Paddle<D>& p : paddles) {
        const Box<D> box = p.box_at(t);
        const Vec<D> paddle_velocity = p.velocity_at(t);
#pragma omp parallel for schedule(static) reduction(+ : pushed)
        for (std::size_t i = 0; i < n; ++i) {
            Vec<D>& x = state.position[i];
            if (!box.contains(x))
                continue;
            // Out through the nearest face, placed on it exactly.
            const Vec<D> normal = box.put_on_nearest_face(x);
            const int a = normal[0] != 0 ? 0 : normal[1] != 0 ? 1 : 2;
            const Real outward = normal[a];
            // Moving into the paddle relative to it: take its normal velocity.
            Real& v = state.velocity[i][a];
            if ((v - paddle_velocity[a]) * outward < 0)
                v = paddle_velocity[a];
            ++pushed;
        }
    }
    return pushed;
}

template struct Paddle<2>;
template struct Paddle<3>;
template PaddleSamples<2> sample_paddles<2>(std::span<const Paddle<2>>, Real, Real, Real);
template PaddleSamples<3> sample_paddles<3>(std::span<const Paddle<3>>, Real, Real, Real);
template void move_paddles<2>(std::span<const Paddle<2>>, Real, BoundaryParticles<2>&);
template void move_paddles<3>(std::span<const Paddle<3>>, Real, BoundaryParticles<3>&);
template std::size_t push_out_of_paddles<2>(std::span<const Paddle<2>>, Real, State<2>&);
template std::size_t push_out_of_paddles<3>(std::span<const Paddle<3>>, Real, State<3>&);

} // namespace sph
