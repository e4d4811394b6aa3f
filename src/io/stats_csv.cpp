#include "io/stats_csv.hpp"

#include "sph/state_hash.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <stdexcept>
#include <unistd.h>

namespace sph {

StatsCsv::StatsCsv(const std::filesystem::path& path) : path_(path) {
    // O_NOFOLLOW: never written through a link (docs/contract.md).
    const int fd =
        ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
    file_ = fd >= 0 ? ::fdopen(fd, "w") : nullptr;
    if (!file_ && fd >= 0)
        ::close(fd);
    if (!file_)
        throw std::runtime_error("cannot write " + path.string());
    fmt::print(file_, "{}\n", header);
    std::fflush(file_);
}

StatsCsv::~StatsCsv() {
    finish();
}

void StatsCsv::write(const Snapshot& f) {
    const FrameStats& s = f.stats;
    // dt columns: the mean, smallest and largest step since the previous
    // frame; iterations: per step, averaged over the same steps.
    const StepCounters& c = f.steps_taken;
    const Real per_step = c.steps ? 1 / Real(c.steps) : 0;
    fmt::print(
        file_,
        "{},{:.9g},{},{:.6g},{},{:.9g},{:.9g},{:.6g},{:.6g},{:.9g},{:.9g},{:.6g},{:.6g},{:.4g},"
        "{:.4g},{},{},{:016x},{:.3f}\n",
        f.frame, f.time, f.steps, c.dt_mean(), s.particles, s.density_avg, s.density_max,
        s.density_error_avg_pct, s.density_error_max_pct, s.kinetic_energy, s.max_speed,
        c.steps ? c.dt_min : 0, c.dt_max, Real(c.pressure_iterations) * per_step,
        Real(c.divergence_iterations) * per_step, c.retries, c.obstacle_pushes, state_hash(f),
        f.wall_seconds);
    if (std::fflush(file_) != 0)
        throw std::runtime_error("cannot write " + path_.string() + " (disk full?)");
}

void StatsCsv::finish() {
    if (file_)
        std::fclose(file_);
    file_ = nullptr;
}

} // namespace sph
