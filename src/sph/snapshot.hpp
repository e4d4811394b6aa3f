#pragma once
// What a frame's consumers (exports, stats, and the renderer) see of the
// simulation: a copy of the particle fields without the dimension in the type.
// The renderer and the writers never touch State or the solver.

#include "sph/diagnostics.hpp"
#include "sph/state.hpp"
#include "sph/step_counters.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace sph {

// Which of a frame's optional fields its consumers read; a field none of
// them reads is neither computed for output nor copied. Positions,
// velocities, densities and ids are always there: stats.csv's figures and
// state hash read them.
struct FrameFields {
    bool pressure = true; // the pressure colour map, the particle exports

    FrameFields& operator|=(const FrameFields& other) {
        pressure = pressure || other.pressure;
        return *this;
    }
};

struct Snapshot {
    int dimension = 2;
    std::uint64_t frame = 0;
    std::uint64_t steps = 0;  // since the start
    Real time = 0;            // s
    StepCounters steps_taken; // since the previous frame: dt range, solver iterations
    Real wall_seconds = 0;    // since the start of the simulation
    FrameStats stats;
    // Particle fields, `dimension` values per particle for vectors.
    std::vector<Real> position, velocity, density;
    std::vector<Real> pressure; // empty when no consumer reads it (FrameFields)
    std::vector<std::uint32_t> id;
    // 1 for particles deep inside the fluid (sph/surface.hpp), which a camera
    // outside it cannot see; empty when not computed.
    std::vector<std::uint8_t> buried;
    // Over MPI ranks, where rank 0's snapshot holds every particle (its own
    // first) and each other rank's only its own: this process's are the
    // first `owned` (what it draws when frames are composited by depth), of
    // `total` in the simulation (0: size()).
    std::size_t owned = std::numeric_limits<std::size_t>::max();
    std::size_t total = 0;

    std::size_t size() const { return density.size(); }
    std::size_t total_particles() const { return total ? total : size(); }
};

template <int D>
void copy_fields(const State<D>& state, Snapshot& snapshot, FrameFields fields = {}) {
    const std::size_t n = state.size();
    snapshot.dimension = D;
    snapshot.position.resize(n * D);
    snapshot.velocity.resize(n * D);
    for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < D; ++a) {
            snapshot.position[i * D + a] = state.position[i][a];
            snapshot.velocity[i * D + a] = state.velocity[i][a];
        }
    snapshot.density = state.density;
    if (fields.pressure)
        snapshot.pressure = state.pressure;
    else
        snapshot.pressure.clear();
    snapshot.id = state.id;
}

} // namespace sph
