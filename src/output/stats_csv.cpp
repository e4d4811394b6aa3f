#include "output/stats_csv.hpp"

#include "output/files.hpp"
#include "sph/state_hash.hpp"

#include <cerrno>
#include <fcntl.h>
#include <fmt/format.h>
#include <stdexcept>
#include <stdio_ext.h>
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
        throw_write_error(path, errno);
    fmt::print(file_, "{}\n", header);
    if (std::fflush(file_) != 0)
        throw_write_error(path, errno);
    complete_bytes_ = std::ftell(file_);
}

StatsCsv::~StatsCsv() {
    finish();
}

void StatsCsv::write(const Snapshot& f) {
    if (!file_)
        throw std::logic_error("cannot write " + path_.string() + ": closed after an error");
    const FrameStats& s = f.stats;
    // dt columns: the mean, smallest and largest step since the previous
    // frame; iterations: per step, averaged over the same steps.
    const StepCounters& c = f.steps_taken;
    const Real per_step = c.steps ? 1 / Real(c.steps) : 0;
    const std::string row = fmt::format(
        "{},{:.9g},{},{:.6g},{},{:.9g},{:.9g},{:.6g},{:.6g},{:.9g},{:.9g},{:.6g},{:.6g},{:.4g},"
        "{:.4g},{},{},{:016x},{:.3f}\n",
        f.frame, f.time, f.steps, c.dt_mean(), s.particles, s.density_avg, s.density_max,
        s.density_error_avg_pct, s.density_error_max_pct, s.kinetic_energy, s.max_speed,
        c.steps ? c.dt_min : 0, c.dt_max, Real(c.pressure_iterations) * per_step,
        Real(c.divergence_iterations) * per_step, c.retries, c.obstacle_pushes, state_hash(f),
        f.wall_seconds);
    if (std::fwrite(row.data(), 1, row.size(), file_) != row.size() || std::fflush(file_) != 0) {
        const int error = errno;
        // What stdio still holds is dropped, so closing writes no more, and
        // the part of the row that reached the file is cut off (shrinking
        // needs no room): the file ends with the last whole row.
        __fpurge(file_);
        if (::ftruncate(fileno(file_), complete_bytes_) != 0) {
            // Left as it is: the last row may then be cut short.
        }
        std::fclose(file_);
        file_ = nullptr;
        throw_write_error(path_, error);
    }
    complete_bytes_ = std::ftell(file_);
}

void StatsCsv::finish() {
    if (file_)
        std::fclose(file_);
    file_ = nullptr;
}

} // namespace sph
