#pragma once
// stats.csv: one row per frame (docs/outputs.md). Rows are flushed as they
// are written, so a run that stops early keeps every frame so far.

#include "output/frame_sink.hpp"

#include <cstdio>
#include <filesystem>

namespace sph {

class StatsCsv final : public FrameSink {
  public:
    explicit StatsCsv(const std::filesystem::path& path);
    ~StatsCsv() override;
    void write(const Snapshot& frame) override;
    void finish() override;

    static constexpr const char* header =
        "frame,time,steps,dt,particles,density_avg,density_max,density_error_avg_pct,"
        "density_error_max_pct,kinetic_energy,max_speed,dt_min,dt_max,pressure_iterations,"
        "divergence_iterations,retries,obstacle_pushes,state_hash,wall_s";

  private:
    std::filesystem::path path_;
    std::FILE* file_ = nullptr;
    long complete_bytes_ = 0; // the header and every whole row written
};

} // namespace sph
