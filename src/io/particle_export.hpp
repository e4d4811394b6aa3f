#pragma once
// Per-frame particle data for analysis tools (`--export csv|vtk`):
//   csv: particles/frame_NNNNN.csv, header x,y[,z],vx,vy[,vz],density,pressure
//   vtk: particles/frame_NNNNN.vtp (VTK XML PolyData) and particles.pvd, the
//        time series ParaView opens; the .pvd is rewritten after every frame so
//        it is valid whenever the run stops.

#include "io/frame_sink.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace sph {

class ParticleCsv final : public FrameSink {
  public:
    // Frames go to folder/particles/.
    explicit ParticleCsv(std::filesystem::path folder) : folder_(std::move(folder)) {}
    void write(const Snapshot& frame) override;
    FrameFields fields() const override { return {.pressure = true}; }

  private:
    std::filesystem::path folder_;
};

class ParticleVtk final : public FrameSink {
  public:
    // Frames go to folder/particles/, the collection to folder/particles.pvd.
    explicit ParticleVtk(std::filesystem::path folder) : folder_(std::move(folder)) {}
    void write(const Snapshot& frame) override;
    FrameFields fields() const override { return {.pressure = true}; }

  private:
    std::filesystem::path folder_;
    std::vector<std::pair<double, std::string>> written_; // time, relative file
};

// "frame_00042" for frame 42.
std::string frame_stem(std::uint64_t frame);

} // namespace sph
