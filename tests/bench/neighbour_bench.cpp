// Neighbour search benchmark: milliseconds per search for the spatial hash
// and the sorted grid, in 2D and 3D, with 1 and 2 threads, on a lattice whose
// particles are stored in a random order (the "shuffled lattice" of
// CompactNSearch's benchmark) and in the sorted grid's cell order (what a
// spatial sort of the particle arrays gives). 3D: spacing dp, radius 2 dp
// (26 neighbours inside the lattice); 2D: radius 2.6 dp (20 neighbours).
// A program that prints a table, not a timed test.
//
//   build/sphclip_bench_neighbours                   # the full table
//   build/sphclip_bench_neighbours --csv FILE        # and write it to FILE
//   build/sphclip_bench_neighbours --quick           # one tiny case each (CI)
//   build/sphclip_bench_neighbours --compactnsearch  # the 125k 3D case alone
#include "bench_support.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fmt/format.h>
#include <fstream>
#include <numeric>
#include <omp.h>
#include <random>
#include <string>
#include <thread>
#include <vector>

using namespace sph;

namespace {

// A power of two, so lattice distances are exact and pairs at exactly 2 dp
// fall out the same way in every search.
constexpr Real spacing = 1.0 / 128;

template <int D>
std::vector<Vec<D>> shuffled_lattice(std::size_t side) {
    std::size_t n = 1;
    for (int a = 0; a < D; ++a)
        n *= side;
    std::vector<Vec<D>> x(n);
    for (std::size_t k = 0; k < n; ++k) {
        std::size_t rest = k;
        for (int a = 0; a < D; ++a, rest /= side)
            x[k][a] = (Real(rest % side) + 0.5) * spacing;
    }
    std::shuffle(x.begin(), x.end(), std::mt19937(7));
    return x;
}

struct Row {
    std::string search, layout;
    int dimension = 0, threads = 0, repetitions = 0;
    std::size_t particles = 0, pairs = 0;
    double radius_dp = 0, ms = 0, build_ms = -1, query_ms = -1;
};

std::string csv(const Row& r) {
    const auto split = [](double ms) {
        return ms < 0 ? std::string() : fmt::format("{:.2f}", ms);
    };
    return fmt::format("{},{},{},{},{},{},{},{:.2f},{},{},{},{:.1f}", r.search, r.dimension,
                       r.particles, r.layout, r.threads, r.radius_dp, r.repetitions, r.ms,
                       split(r.build_ms), split(r.query_ms), r.pairs,
                       r.pairs / (r.ms * 1e-3) * 1e-6);
}

// Median over repetitions after one warm-up call (allocations, page faults):
// at least 3 and about a second's worth, fewer when calls take seconds, and
// only the warm-up itself when it took over 10 s (the hash on a large
// shuffled lattice).
template <int D>
Row measure(NeighbourSearch<D>& search, const std::vector<Vec<D>>& x, Real radius, bool quick) {
    NeighbourList list;
    struct Sample {
        double ms, build_ms, query_ms;
    };
    std::vector<Sample> samples;
    auto* grid = dynamic_cast<SortedGrid<D>*>(&search);
    const auto once = [&] {
        const auto start = std::chrono::steady_clock::now();
        search.find(x, radius, list);
        const double ms =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count();
        if (grid)
            samples.push_back({ms, grid->last_timings().build_seconds * 1e3,
                               grid->last_timings().query_seconds * 1e3});
        else
            samples.push_back({ms, -1, -1});
    };
    once();
    if (!quick && samples[0].ms < 10000) {
        samples.clear();
        double total = 0;
        do {
            once();
            total += samples.back().ms;
        } while (total < 10000 && (samples.size() < 3 || (total < 1000 && samples.size() < 21)));
    }
    std::sort(samples.begin(), samples.end(),
              [](const Sample& a, const Sample& b) { return a.ms < b.ms; });
    const Sample& median = samples[samples.size() / 2];
    Row row;
    row.search = std::string(search.name());
    row.dimension = D;
    row.particles = x.size();
    row.repetitions = static_cast<int>(samples.size());
    row.pairs = list.pair_count();
    row.ms = median.ms;
    row.build_ms = median.build_ms;
    row.query_ms = median.query_ms;
    return row;
}

// Both searches, both layouts, 1 and 2 threads, for one lattice. Returns
// false if the searches disagree on a pair count.
template <int D>
bool run_case(std::size_t side, Real radius_dp, bool quick, std::vector<Row>& rows,
              std::FILE* out) {
    const Real radius = radius_dp * spacing;
    const std::vector<Vec<D>> shuffled = shuffled_lattice<D>(side);
    // The same lattice stored in the grid's cell order.
    std::vector<Vec<D>> sorted(shuffled.size());
    {
        SortedGrid<D> grid;
        NeighbourList list;
        grid.find(shuffled, radius, list);
        for (std::size_t k = 0; k < sorted.size(); ++k)
            sorted[k] = shuffled[grid.order()[k]];
    }
    bool agree = true;
    for (const char* layout : {"shuffled", "cell_order"}) {
        const auto& x = std::strcmp(layout, "shuffled") == 0 ? shuffled : sorted;
        for (int threads : {1, 2}) {
            omp_set_num_threads(threads);
            SpatialHash<D> hash;
            SortedGrid<D> grid;
            Row by_hash = measure<D>(hash, x, radius, quick);
            Row by_grid = measure<D>(grid, x, radius, quick);
            agree = agree && by_hash.pairs == by_grid.pairs;
            for (Row* r : {&by_hash, &by_grid}) {
                r->layout = layout;
                r->threads = threads;
                r->radius_dp = radius_dp;
                fmt::print(out, "{}\n", csv(*r));
                std::fflush(out);
                rows.push_back(*r);
            }
        }
    }
    return agree;
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    bool peer_case_only = false;
    std::string csv_path;
    for (int k = 1; k < argc; ++k) {
        if (std::strcmp(argv[k], "--quick") == 0)
            quick = true;
        else if (std::strcmp(argv[k], "--compactnsearch") == 0)
            peer_case_only = true;
        else if (std::strcmp(argv[k], "--csv") == 0 && k + 1 < argc)
            csv_path = argv[++k];
        else {
            fmt::print(stderr, "usage: {} [--quick | --compactnsearch] [--csv FILE]\n", argv[0]);
            return 2;
        }
    }

    const std::string header = fmt::format(
        "# sphclip_bench_neighbours, {}, {} cores (nproc), {}, g++ {}.{}, {}\n"
        "# lattice at spacing dp stored in a random order (shuffled) or in the grid's cell "
        "order; 3D radius 2 dp, 2D radius 2.6 dp; pairs counted both ways (i, j) and (j, i); "
        "ms: median per search\n"
        "search,dimension,particles,layout,threads,radius_dp,repetitions,ms,build_ms,query_ms,"
        "pairs,mpairs_per_s\n",
        bench::now_utc("%Y-%m-%d"), std::thread::hardware_concurrency(), bench::cpu_model(),
        __GNUC__, __GNUC_MINOR__,
        quick            ? "--quick"
        : peer_case_only ? "--compactnsearch"
                         : "full");
    fmt::print("{}", header);

    const int before = omp_get_max_threads();
    std::vector<Row> rows;
    bool agree = true;
    // 3D: ~10k, ~100k, 125k (CompactNSearch's case) and 1M particles; 2D: ~10k, ~100k, 1M.
    // --compactnsearch: the 125k 3D case alone, the one compared with the peer.
    const std::vector<std::size_t> sides3 = quick ? std::vector<std::size_t>{8}
                                            : peer_case_only
                                                ? std::vector<std::size_t>{50}
                                                : std::vector<std::size_t>{22, 46, 50, 100};
    const std::vector<std::size_t> sides2 = quick ? std::vector<std::size_t>{24}
                                            : peer_case_only
                                                ? std::vector<std::size_t>{}
                                                : std::vector<std::size_t>{100, 316, 1000};
    for (std::size_t side : sides3)
        agree = run_case<3>(side, 2.0, quick, rows, stdout) && agree;
    for (std::size_t side : sides2)
        agree = run_case<2>(side, 2.6, quick, rows, stdout) && agree;
    omp_set_num_threads(before);

    if (!csv_path.empty()) {
        std::ofstream file(csv_path);
        file << header;
        for (const Row& r : rows)
            file << csv(r) << '\n';
        if (!file) {
            fmt::print(stderr, "cannot write {}\n", csv_path);
            return 1;
        }
    }
    if (!agree) {
        fmt::print(stderr, "the hash and the sorted grid found different pair counts\n");
        return 1;
    }
    return 0;
}
