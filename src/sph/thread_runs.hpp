#pragma once
// A pass over items in order, split among the threads of a parallel region
// as one run of consecutive items each, the runs of about equal work,
// rather than chunks dealt out as threads come free: a thread then reads
// mostly what it wrote itself in the pass before, from its own core's
// cache (docs/benchmarks.md, "The solves' loads": dfsph's solves 15-20%
// faster than with chunks of 32 slices, wcsph's 2D cell passes 3-10%).

#include <cstddef>
#include <cstdint>
#include <omp.h>
#include <ranges>

namespace sph {

// This thread's run of the items [0, count), inside a parallel region:
// work_before(k) is the work of the items before item k (non-decreasing in
// k), total that of all of them.
template <class WorkBefore>
auto this_thread_run(std::size_t count, std::uint64_t total, const WorkBefore& work_before) {
    const auto threads = std::size_t(omp_get_num_threads());
    const auto thread = std::size_t(omp_get_thread_num());
    // The first item with at least t / threads of the work before it.
    const auto bound = [&](std::size_t t) {
        if (t >= threads)
            return count;
        const std::uint64_t wanted = total * t / threads;
        std::size_t low = 0, high = count;
        while (low < high) {
            const std::size_t middle = low + (high - low) / 2;
            if (std::uint64_t(work_before(middle)) < wanted)
                low = middle + 1;
            else
                high = middle;
        }
        return low;
    };
    return std::views::iota(bound(thread), bound(thread + 1));
}

} // namespace sph
