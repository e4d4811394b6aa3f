#pragma once
// Boundaries: the solids that keep the fluid in (the domain box's walls) or
// out (obstacles, paddles). A boundary enters the physics in two ways:
// - as particles (Akinci et al. 2012, boundary_particles.hpp), when the walls
//   are particles or the scene has obstacles or paddles: the solvers sum them
//   into density and pressure like fluid;
// - as the last guard (last_guard below), after every move: a particle found
//   inside a solid at the end of a step is put back on its surface and its
//   velocity into it turned or taken away. The particles alone cannot
//   promise it: a thin film with few neighbours only reaches the rest
//   density close to them, and a reflecting box has no particles at all.
// The step holds one list of them, built once from the scene
// (boundary_set.hpp): a kind the scene does not have is not in the list.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/stage_times.hpp"
#include "sph/state.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

namespace sph {

template <int D>
class Boundary {
  public:
    virtual ~Boundary() = default;
    // The key naming it in the scene ("walls" for solver.walls, "obstacles"
    // and "paddles" for effects.*), and its stage in the stage table.
    virtual std::string_view name() const = 0;
    // Puts back the particles found inside it at time t (the end of a step),
    // the last guard; returns how many of them count as pushes in stats.csv
    // (obstacle_pushes: obstacles and paddles, not the box's reflections).
    virtual std::size_t keep_out(Real t, State<D>& state) const = 0;
    // Whether its particles move (a paddle), and placing them where they are
    // at time t, with their velocities, in the boundary particle set.
    virtual bool moves() const { return false; }
    virtual void place(Real /*t*/, BoundaryParticles<D>& /*particles*/) const {}
    // The largest speed it ever moves the fluid beside it with (m/s), known
    // before any step, for the time step's first estimate.
    virtual Real speed() const { return 0; }
};

template <int D>
using BoundaryList = std::vector<std::unique_ptr<Boundary<D>>>;

// The last guard every solver ends its step with, shared by all kinds: each
// boundary in the list's order (the box's walls, the obstacles, the paddles)
// puts back the particles found inside it at time t, timed under its own
// name (into `stages` unless null). Returns the pushes stats.csv counts.
template <int D>
std::uint64_t last_guard(const BoundaryList<D>& boundaries, Real t, State<D>& state,
                         StageTimes* stages = nullptr) {
    std::uint64_t pushed = 0;
    for (const auto& boundary : boundaries) {
        StageTimes::Scope timed(stages, StageName::of(*boundary));
        pushed += boundary->keep_out(t, state);
    }
    return pushed;
}

} // namespace sph
