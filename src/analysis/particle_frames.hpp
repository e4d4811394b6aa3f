#pragma once
// Particle data a run exported with `--export csv` (particles/frame_NNNNN.csv),
// and the particles that belong to the body of the fluid rather than to spray.

#include <cstddef>
#include <filesystem>
#include <vector>

namespace sph {

struct ParticleFrame {
    int dimension = 2;
    std::vector<double> position; // x, y[, z] per particle
    std::vector<double> velocity; // vx, vy[, vz] per particle
    std::vector<double> density;  // kg/m^3
    std::vector<double> pressure; // Pa

    std::size_t size() const { return density.size(); }
    double coordinate(std::size_t i, int axis) const { return position[i * dimension + axis]; }
    double speed(std::size_t i) const;
};

// Reads one exported frame; the dimension follows from the header (a z column
// means 3D). Throws std::runtime_error for a missing file or column.
ParticleFrame read_particle_frame(const std::filesystem::path& path);

// particles/frame_*.csv of the run folder `run`, in frame order.
std::vector<std::filesystem::path> particle_frame_files(const std::filesystem::path& run);

// N of ".../frame_N.csv".
std::size_t particle_frame_number(const std::filesystem::path& file);

// True for each particle with at least one other particle within `radius`:
// a lone droplet thrown ahead of the surge, or above the surface, is false.
// Cell list with cells of size `radius`, so it costs O(n).
std::vector<bool> has_neighbour_within(const ParticleFrame& frame, double radius);

} // namespace sph
