#pragma once
// What a frame's consumers (exports, stats, and the renderer) see of the
// simulation: a copy of the particle fields without the dimension in the type.
// The renderer and the writers never touch State or the solver.

#include "sph/diagnostics.hpp"
#include "sph/state.hpp"
#include "sph/step_counters.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace sph {

struct Snapshot {
    int dimension = 2;
    std::uint64_t frame = 0;
    std::uint64_t steps = 0;  // since the start
    Real time = 0;            // s
    StepCounters steps_taken; // since the previous frame: dt range, solver iterations
    Real wall_seconds = 0;    // since the start of the simulation
    FrameStats stats;
    // Particle fields, `dimension` values per particle for vectors.
    std::vector<Real> position, velocity, density, pressure;
    std::vector<std::uint32_t> id;
    // 1 for particles deep inside the fluid (sph/surface.hpp), which a camera
    // outside it cannot see; empty when not computed.
    std::vector<std::uint8_t> buried;

    std::size_t size() const { return density.size(); }
};

template <int D>
void copy_fields(const State<D>& state, Snapshot& snapshot) {
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
    snapshot.pressure = state.pressure;
    snapshot.id = state.id;
}

} // namespace sph
