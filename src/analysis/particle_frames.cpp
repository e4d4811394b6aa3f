#include "analysis/particle_frames.hpp"

#include "analysis/csv_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace sph {

namespace fs = std::filesystem;

double ParticleFrame::speed(std::size_t i) const {
    double s2 = 0;
    for (int a = 0; a < dimension; ++a)
        s2 += velocity[i * dimension + a] * velocity[i * dimension + a];
    return std::sqrt(s2);
}

ParticleFrame read_particle_frame(const fs::path& path) {
    const CsvTable table = read_csv_table(path);
    ParticleFrame frame;
    frame.dimension = table.has("z") ? 3 : 2;
    const int dim = frame.dimension;
    const char* axes[] = {"x", "y", "z"};
    const char* velocities[] = {"vx", "vy", "vz"};
    const std::size_t n = table.rows();
    frame.position.resize(n * dim);
    frame.velocity.resize(n * dim);
    for (int a = 0; a < dim; ++a) {
        const auto& x = table.column(axes[a]);
        const auto& v = table.column(velocities[a]);
        for (std::size_t i = 0; i < n; ++i) {
            frame.position[i * dim + a] = x[i];
            frame.velocity[i * dim + a] = v[i];
        }
    }
    frame.density = table.column("density");
    frame.pressure = table.column("pressure");
    return frame;
}

std::vector<fs::path> particle_frame_files(const fs::path& run) {
    std::vector<fs::path> files;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(run / "particles", ec)) {
        const std::string name = entry.path().filename().string();
        if (name.starts_with("frame_") && entry.path().extension() == ".csv")
            files.push_back(entry.path());
    }
    // frame_NNNNN: zero-padded, so the name order is the frame order.
    std::sort(files.begin(), files.end());
    return files;
}

std::size_t particle_frame_number(const fs::path& file) {
    return std::stoul(file.stem().string().substr(std::string("frame_").size()));
}

std::vector<bool> has_neighbour_within(const ParticleFrame& frame, double radius) {
    const int dim = frame.dimension;
    const std::size_t n = frame.size();
    using Cell = std::array<std::int64_t, 3>;
    auto cell_of = [&](std::size_t i) {
        Cell c{0, 0, 0};
        for (int a = 0; a < dim; ++a)
            c[a] = std::int64_t(std::floor(frame.coordinate(i, a) / radius));
        return c;
    };
    struct CellHash {
        std::size_t operator()(const Cell& c) const {
            return std::size_t(c[0] * 73856093 ^ c[1] * 19349663 ^ c[2] * 83492791);
        }
    };
    std::unordered_map<Cell, std::vector<std::size_t>, CellHash> cells;
    for (std::size_t i = 0; i < n; ++i)
        cells[cell_of(i)].push_back(i);

    const double r2 = radius * radius;
    std::vector<bool> result(n, false);
    const int reach_z = dim == 3 ? 1 : 0;
    for (std::size_t i = 0; i < n; ++i) {
        const Cell c = cell_of(i);
        for (int dx = -1; dx <= 1 && !result[i]; ++dx)
            for (int dy = -1; dy <= 1 && !result[i]; ++dy)
                for (int dz = -reach_z; dz <= reach_z && !result[i]; ++dz) {
                    const auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
                    if (it == cells.end())
                        continue;
                    for (std::size_t j : it->second) {
                        if (j == i)
                            continue;
                        double d2 = 0;
                        for (int a = 0; a < dim; ++a) {
                            const double d = frame.coordinate(i, a) - frame.coordinate(j, a);
                            d2 += d * d;
                        }
                        if (d2 <= r2) {
                            result[i] = true;
                            break;
                        }
                    }
                }
    }
    return result;
}

} // namespace sph
