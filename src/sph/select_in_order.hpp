#pragma once
// A filter over runs of indices by every thread, whose list is the one a
// plain loop would give: each thread counts the kept indices of its share,
// then writes them from where the shares before it end. For the lists a
// step builds from many candidates (the walls near the fluid, the occupied
// cells of a sort), which one thread built while the others waited.

#include "sph/headroom.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <omp.h>
#include <vector>

namespace sph {

class SelectInOrder {
  public:
    // Forgets the runs added before.
    void clear() { runs_.clear(); }
    // The indices begin .. end - 1, after those added before.
    void add(std::uint32_t begin, std::uint32_t end) {
        if (end > begin)
            runs_.push_back({begin, end});
    }
    // Appends to `out` every index of the runs, in their order, for which
    // keep(index) is true. Each thread takes an even share of the indices
    // (a run may be cut between two). Allocates nothing once sizes settle.
    template <class Keep>
    void append_to(std::vector<std::uint32_t>& out, const Keep& keep) {
        run_start_.resize(runs_.size() + 1);
        run_start_[0] = 0;
        for (std::size_t r = 0; r < runs_.size(); ++r)
            run_start_[r + 1] = run_start_[r] + (runs_[r].end - runs_[r].begin);
        const std::size_t total = run_start_.back(), base = out.size();
        const int threads = omp_get_max_threads();
        kept_.resize(std::size_t(threads));
#pragma omp parallel num_threads(threads)
        {
            const auto t = std::size_t(omp_get_thread_num());
            const auto count = std::size_t(omp_get_num_threads());
            const std::size_t from = total * t / count, to = total * (t + 1) / count;
            // keep(b) for the indices of entries from .. to - 1 of the runs
            // laid end to end.
            const auto each = [&](const auto& visit) {
                std::size_t r = 0;
                while (r < runs_.size() && run_start_[r + 1] <= from)
                    ++r;
                for (; r < runs_.size() && run_start_[r] < to; ++r) {
                    const std::size_t first = std::max(from, run_start_[r]);
                    const std::size_t last = std::min(to, run_start_[r + 1]);
                    const std::uint32_t begin = runs_[r].begin;
                    for (std::size_t e = first; e < last; ++e)
                        visit(static_cast<std::uint32_t>(begin + (e - run_start_[r])));
                }
            };
            std::size_t kept = 0;
            each([&](std::uint32_t b) { kept += keep(b) ? 1 : 0; });
            kept_[t] = kept;
#pragma omp barrier
#pragma omp single
            {
                std::size_t all = 0;
                for (std::size_t u = 0; u < count; ++u)
                    all += kept_[u];
                resize_with_headroom(out, base + all);
            }
            std::size_t at = base;
            for (std::size_t u = 0; u < t; ++u)
                at += kept_[u];
            std::uint32_t* const list = out.data();
            each([&](std::uint32_t b) {
                if (keep(b))
                    list[at++] = b;
            });
        }
    }

  private:
    struct Run {
        std::uint32_t begin, end;
    };
    std::vector<Run> runs_;
    std::vector<std::size_t> run_start_; // entries before each run, and the total
    std::vector<std::size_t> kept_;      // per thread
};

} // namespace sph
