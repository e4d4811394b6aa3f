#pragma once
// Paddles: boxes that move with a prescribed motion (the scene's
// effects.paddles), a piston wavemaker for sloshing and waves. Like a static
// box obstacle (obstacles.hpp) a paddle is a shell of boundary particles
// (Akinci et al. 2012), sampled once at rest; every step they are placed
// where the motion has them at the step's time and carry its velocity, known
// in closed form. The solvers see them in the one BoundaryParticles set,
// after the static particles, with a search grid of their own that is
// rebuilt when they move (the static grid stays as built).
//
// A moving boundary particle enters the physics through its velocity v_b:
// the density sum is unchanged (it depends on positions only), dfsph's
// divergence and density sources use v_i - v_b (Bender & Koschier 2017,
// eq. 8 with Akinci's boundary term), the Morris and Monaghan viscosities
// use v_i - v_b (no slip on the moving wall), wcsph's pressure force is
// unchanged. A static particle has v_b = 0 and the arithmetic of a static
// wall is unchanged.

#include "sph/boundaries/boundary.hpp"
#include "sph/state.hpp"
#include "sph/vec.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace sph {

enum class PaddleMotion {
    sine,  // d(t) = A sin(2 pi (t - start) / T) from `start` on: a piston wavemaker
    linear // d(t) = V (t - start) between `start` and `end`, then held: a pushing piston
};

template <int D>
struct Paddle {
    Box<D> box; // m, where it is at rest: before `start`, and at d = 0
    PaddleMotion motion = PaddleMotion::sine;
    Vec<D> amplitude{0}; // m, sine: the largest displacement (half the stroke)
    Real period = 1;     // s, sine
    Vec<D> velocity{0};  // m/s, linear
    Real start = 0;      // s, when it starts moving
    Real end = std::numeric_limits<Real>::infinity(); // s, linear: when it stops

    // Displacement from the rest box at time t (m), and its rate (m/s).
    Vec<D> displacement(Real t) const;
    Vec<D> velocity_at(Real t) const;
    // The largest speed the motion ever has (m/s): |A| 2 pi / T or |V|.
    Real peak_speed() const;
    // The box at time t.
    Box<D> box_at(Real t) const;
};

// The paddles' shells at rest, sampled as box obstacles are (obstacles.hpp):
// positions, volumes, and which paddle each sample belongs to. Each paddle
// is sampled alone: paddles that touch at rest may move apart.
template <int D>
struct PaddleSamples {
    std::vector<Vec<D>> positions;
    std::vector<Real> volumes;
    std::vector<std::uint32_t> paddle;
};

template <int D>
PaddleSamples<D> sample_paddles(std::span<const Paddle<D>> paddles, Real spacing, Real h,
                                Real lattice_volume);

// Places the moving particles of `boundary` (its paddles' samples) where the
// motions have them at time t, with their velocities, and refreshes their
// search grid.
template <int D>
void move_paddles(std::span<const Paddle<D>> paddles, Real t, BoundaryParticles<D>& boundary);

// The last guard after each move, as push_out_of_obstacles is for static
// solids: a particle found inside a paddle's box at time t (the end of the
// step) is put on its nearest face, and a velocity into the paddle, relative
// to it, loses that component: the particle leaves with the paddle's normal
// velocity (v.n = v_b.n), not reflected as off a wall at rest. Returns how
// many were put back.
template <int D>
std::size_t push_out_of_paddles(std::span<const Paddle<D>> paddles, Real t, State<D>& state);

// The scene's paddles in the boundary list (present when it has any): their
// particles are the boundary set's moving ones.
template <int D>
class PaddleSet final : public Boundary<D> {
  public:
    explicit PaddleSet(std::vector<Paddle<D>> paddles) : paddles_(std::move(paddles)) {}
    std::string_view name() const override { return "paddles"; }
    std::size_t keep_out(Real t, State<D>& state) const override {
        return push_out_of_paddles<D>(paddles_, t, state);
    }
    bool moves() const override { return true; }
    void place(Real t, BoundaryParticles<D>& particles) const override {
        move_paddles<D>(paddles_, t, particles);
    }
    // A paddle moves the fluid beside it as fast as it goes itself.
    Real speed() const override {
        Real fastest = 0;
        for (const Paddle<D>& paddle : paddles_)
            fastest = std::max(fastest, paddle.peak_speed());
        return fastest;
    }

  private:
    std::vector<Paddle<D>> paddles_;
};

} // namespace sph
