#pragma once
// Per-frame particle data for analysis tools (`--export csv|vtk|vtk-ascii`):
//   csv: particles/frame_NNNNN.csv, header
//        x,y[,z],vx,vy[,vz],density,pressure,id,time (SI units, docs/outputs.md)
//   vtk: particles/frame_NNNNN.vtp (VTK XML PolyData) and particles.pvd, the
//        time series ParaView opens; the .pvd is rewritten after every frame so
//        it is valid whenever the run stops. Binary by default: every array
//        in one appended block, zlib-compressed (VTK's vtkZLibDataCompressor
//        layout); vtk-ascii writes the same arrays as text.

#include "output/frame_sink.hpp"

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
    enum class Encoding { binary, ascii };
    // Frames go to folder/particles/, the collection to folder/particles.pvd.
    explicit ParticleVtk(std::filesystem::path folder, Encoding encoding = Encoding::binary)
        : folder_(std::move(folder)), encoding_(encoding) {}
    void write(const Snapshot& frame) override;
    FrameFields fields() const override { return {.pressure = true}; }

  private:
    std::filesystem::path folder_;
    Encoding encoding_;
    std::vector<std::pair<double, std::string>> written_; // time, relative file
};

// "frame_00042" for frame 42.
std::string frame_stem(std::uint64_t frame);

} // namespace sph
