// Rendering over MPI ranks (docs/mpi.md, "Rendering over ranks"): the time
// of a frame on rank 0 when
//   (a) gather: the ranks send rank 0 what drawing needs of their particles
//       (an MPI_Gatherv of 4 floats a particle: position and the colour's
//       scalar) and rank 0 draws every particle, against
//   (b) depth: each rank draws the particles it owns into a layer, sends it,
//       and rank 0 composites the layers by depth (render.mpi_composite =
//       depth, the renderer's own path),
// by particle count, image size and layout, on this job's ranks. Today every
// rank holds the whole state and the run's gather path sends nothing, so (a)
// times the Gatherv on its own and adds it to rank 0's drawing: the figure
// the choice must hold for once the state is distributed. The two paths take
// turns frame by frame (a change in a shared machine's load touches both);
// each case checks that their frames are the same pixels. A program that
// prints a table, not a timed test.
//
//   mpirun -np 2 build/sphclip_bench_composite                 # the table
//   mpirun -np 2 build/sphclip_bench_composite --csv FILE      # ... also to FILE
//   mpirun -np 2 build/sphclip_bench_composite --counts 10000 --sizes 640x360
//       --layouts block,scattered --backends egl,osmesa --frames 5
//   mpirun -np 2 build/sphclip_bench_composite --png FOLDER    # ... and each case's frames
//   mpirun -np 2 build/sphclip_bench_composite --tiny          # one small case (CI)
#include "bench_particles.hpp"
#include "bench_support.hpp"
#include "output/png_io.hpp"
#include "parallel/render_exchange.hpp"
#include "parallel/world.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <memory>
#include <mpi.h>
#include <sched.h>
#include <string>
#include <thread>
#include <utility>
#include <vector>

using namespace sph;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The CPUs this process may run on (mpirun's binding: one core a rank by
// default at 2 ranks, all with --bind-to none).
int cpus_allowed() {
    cpu_set_t set;
    CPU_ZERO(&set);
    return sched_getaffinity(0, sizeof set, &set) == 0 ? CPU_COUNT(&set) : -1;
}

// The process's threads now (after a GL context is made: llvmpipe's
// rasteriser threads among them).
int thread_count() {
    int n = 0;
    for ([[maybe_unused]] const auto& entry :
         std::filesystem::directory_iterator("/proc/self/task"))
        ++n;
    return n;
}

// The particles rank r of P owns in a frame of n: [n r / P, n (r + 1) / P),
// an even cut as a run's partition makes it.
std::pair<std::size_t, std::size_t> owned_range(std::size_t n, int rank, int ranks) {
    return {n * std::size_t(rank) / std::size_t(ranks),
            n * std::size_t(rank + 1) / std::size_t(ranks)};
}

// What a rank's renderer sees of a frame in a run: rank 0 every particle,
// its own first; the others their own only.
Snapshot rank_frame(const Snapshot& whole) {
    const auto [first, last] = owned_range(whole.size(), parallel::rank(), parallel::size());
    Snapshot own;
    if (parallel::leader()) {
        own = whole;
    } else {
        own.dimension = whole.dimension;
        const auto d = std::ptrdiff_t(whole.dimension);
        const auto slice = [&](const auto& from, auto& to, std::ptrdiff_t per) {
            to.assign(from.begin() + std::ptrdiff_t(first) * per,
                      from.begin() + std::ptrdiff_t(last) * per);
        };
        slice(whole.position, own.position, d);
        slice(whole.velocity, own.velocity, d);
        slice(whole.density, own.density, 1);
        if (!whole.pressure.empty())
            slice(whole.pressure, own.pressure, 1);
        slice(whole.id, own.id, 1);
        if (!whole.buried.empty())
            slice(whole.buried, own.buried, 1);
    }
    own.owned = last - first;
    own.total = whole.size();
    return own;
}

// What rank 0 needs to draw a particle once the state is distributed: its
// position and its colour's scalar (the speed), 4 floats. Every rank packs
// its owned range and rank 0 gathers them all.
class ParticleGather {
  public:
    explicit ParticleGather(std::size_t n) : n_(n) {
        const int ranks = parallel::size();
        counts_.resize(std::size_t(ranks));
        offsets_.resize(std::size_t(ranks));
        for (int r = 0; r < ranks; ++r) {
            const auto [first, last] = owned_range(n, r, ranks);
            counts_[std::size_t(r)] = int(4 * (last - first));
            offsets_[std::size_t(r)] = int(4 * first);
        }
        if (parallel::leader())
            all_.resize(4 * n);
    }
    void gather(const Snapshot& s) {
        const auto [first, last] = owned_range(n_, parallel::rank(), parallel::size());
        own_.resize(4 * (last - first));
        for (std::size_t i = first; i < last; ++i) {
            float* out = own_.data() + 4 * (i - first);
            const Real* p = &s.position[3 * i];
            const Real* v = &s.velocity[3 * i];
            out[0] = float(p[0]);
            out[1] = float(p[1]);
            out[2] = float(p[2]);
            out[3] = float(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
        }
        MPI_Gatherv(own_.data(), int(own_.size()), MPI_FLOAT, all_.data(), counts_.data(),
                    offsets_.data(), MPI_FLOAT, 0, MPI_COMM_WORLD);
    }

  private:
    std::size_t n_;
    std::vector<int> counts_, offsets_;
    std::vector<float> own_, all_;
};

struct Case {
    std::string layout;
    std::size_t particles;
    int width, height;
};

} // namespace

int main(int argc, char** argv) {
    parallel::Session session(&argc, &argv);
    const bool leader = parallel::leader();
    bench::CommonOptions options;
    options.backends = "egl";
    std::string sizes = "640x360,1280x720", layouts = "block";
    int frames = 5;
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        if (options.take(k, argc, argv))
            continue;
        if (arg == "--sizes" && k + 1 < argc)
            sizes = argv[++k];
        else if (arg == "--layouts" && k + 1 < argc)
            layouts = argv[++k];
        else if (arg == "--frames" && k + 1 < argc && std::atoi(argv[k + 1]) > 0)
            frames = std::atoi(argv[++k]);
        else {
            if (leader)
                fmt::print(stderr,
                           "usage: mpirun -np N {} [--tiny] [--counts N,N] [--sizes WxH,WxH] "
                           "[--layouts block,scattered] [--backends egl,osmesa] [--frames K] "
                           "[--csv FILE] [--png FOLDER]\n",
                           argv[0]);
            return 2;
        }
    }
    if (parallel::size() < 2) {
        fmt::print(stderr,
                   "{}: run it under mpirun -np 2 (or more): it compares the ranks' "
                   "two ways of drawing a frame\n",
                   argv[0]);
        return 77; // ctest's skip
    }
    if (options.tiny) {
        options.counts = options.counts.empty() ? "2000" : options.counts;
        sizes = "320x180";
        frames = 1;
    }
    const std::vector<std::size_t> counts = options.particle_counts({10000, 100000, 1000000});
    std::vector<Case> cases;
    for (const std::string& layout : bench::split_list(layouts))
        for (const std::string& size : bench::split_list(sizes))
            for (std::size_t n : counts) {
                int w = 0, h = 0;
                if (std::sscanf(size.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0) {
                    if (leader)
                        fmt::print(stderr, "--sizes: {} is not WxH\n", size);
                    return 2;
                }
                cases.push_back({layout, n, w, h});
            }

    std::FILE* csv = nullptr;
    if (leader && !options.csv.empty() && !(csv = std::fopen(options.csv.c_str(), "w"))) {
        fmt::print(stderr, "cannot write {}\n", options.csv);
        return parallel::end_job(2);
    }
    auto note = [&](const std::string& line) {
        if (!leader)
            return;
        fmt::print("# {}\n", line);
        if (csv)
            fmt::print(csv, "# {}\n", line);
    };
    auto emit = [&](const std::string& line) {
        if (!leader)
            return;
        fmt::print("{}\n", line);
        std::fflush(stdout);
        if (csv) {
            fmt::print(csv, "{}\n", line);
            std::fflush(csv);
        }
    };
    const char* lp_threads = std::getenv("LP_NUM_THREADS");
    note(fmt::format("sphclip_bench_composite, {}, {} ranks", bench::now_utc(), parallel::size()));
    note(fmt::format("{} cores (nproc), {}; each rank may run on {} CPUs (mpirun's binding)",
                     std::thread::hardware_concurrency(), bench::cpu_model(), cpus_allowed()));
    note(fmt::format("LP_NUM_THREADS {}", lp_threads ? lp_threads : "unset (llvmpipe's default)"));
    note(fmt::format("load average (1, 5, 15 min) at the start: {}", bench::load_average()));
    note("gather_ms: MPI_Gatherv of 4 floats a particle to rank 0; draw_all_ms: rank 0 draws "
         "every particle; gather_path_ms = the two; depth_path_ms: every rank draws its own, "
         "rank 0 composites (composite_ms of it on rank 0: its layer, waiting for and writing "
         "in the others'); medians over the frames; ratio = depth_path_ms / gather_path_ms");
    emit("backend,cpus_per_rank,layout,particles,drawn,width,height,frames,gather_ms,draw_all_ms,"
         "gather_path_ms,depth_path_ms,composite_ms,layer_mb_per_rank,ratio,identical");

    // Composite every frame (from 0 particles on); made on every rank at once.
    const std::unique_ptr<RankCompositing> exchange = parallel::make_render_exchange(0);
    bool all_identical = true;
    for (const std::string& backend : bench::split_list(options.backends)) {
        auto context = make_gl_context(backend);
        note(fmt::format("{}: {}, OpenGL {}; {} threads in rank 0's process with its context",
                         backend, context->info().renderer, context->info().version,
                         thread_count()));
        for (const Case& c : cases) {
            const bool block = c.layout != "scattered";
            // The spacing shrinks with the count in a fixed 0.1 m box, as in
            // render_bench: the block's spheres ~8 px across at 100k.
            const double box = 0.1, spacing = box / std::ceil(std::cbrt(double(c.particles)));
            const Snapshot s = bench::make_particles(c.particles, block, spacing, box);
            const Snapshot mine = rank_frame(s);
            RenderSettings r;
            r.width = c.width;
            r.height = c.height;
            r.dimension = 3;
            r.radius = 0.5 * spacing;
            r.range = {0, 2};
            r.domain_min = glm::dvec3(0);
            r.domain_max = glm::dvec3(box);
            r.cull_buried = block;
            // render_bench's camera: the whole box in view but for the
            // block's nearest bottom corner.
            r.camera_target = glm::dvec3(0.05);
            r.camera_position = glm::dvec3(0.05) + 0.2 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
            std::unique_ptr<FrameRenderer> whole;
            if (leader)
                whole = std::make_unique<FrameRenderer>(r);
            FrameRenderer by_depth(r);
            by_depth.share_over_ranks(exchange.get());
            ParticleGather gather(c.particles);

            std::vector<double> gather_ms, draw_ms, gather_path_ms, depth_ms, composite_ms;
            Image plain, composited;
            // One frame of each first (shaders, buffers), not counted.
            for (int k = -1; k < frames; ++k) {
                MPI_Barrier(MPI_COMM_WORLD);
                auto start = Clock::now();
                gather.gather(s);
                const double g = ms_since(start);
                if (leader) {
                    const auto draw_start = Clock::now();
                    plain = whole->render(s);
                    const double d = ms_since(draw_start);
                    if (k >= 0) {
                        gather_ms.push_back(g);
                        draw_ms.push_back(d);
                        gather_path_ms.push_back(g + d);
                    }
                }
                MPI_Barrier(MPI_COMM_WORLD);
                start = Clock::now();
                composited = by_depth.render(mine);
                if (leader && k >= 0) {
                    depth_ms.push_back(ms_since(start));
                    composite_ms.push_back(by_depth.last_composite_seconds() * 1e3);
                }
            }
            if (!leader)
                continue;
            if (!options.png.empty()) {
                std::filesystem::create_directories(options.png);
                const std::string name = fmt::format("{}-{}-{}-{}x{}", backend, c.layout,
                                                     c.particles, c.width, c.height);
                write_png(std::filesystem::path(options.png) / (name + "-gather.png"), plain);
                write_png(std::filesystem::path(options.png) / (name + "-depth.png"), composited);
            }
            const bool identical = plain.width == composited.width &&
                                   plain.height == composited.height &&
                                   plain.rgba == composited.rgba;
            all_identical = all_identical && identical;
            const double layer_mb = double(c.width) * c.height * r.samples * 8 / 1e6;
            const double ratio = bench::median(depth_ms) / bench::median(gather_path_ms);
            emit(fmt::format(
                "{},{},{},{},{},{},{},{},{:.2f},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.2f},"
                "{}",
                backend, cpus_allowed(), c.layout, c.particles, whole->last_drawn(), c.width,
                c.height, frames, bench::median(gather_ms), bench::median(draw_ms),
                bench::median(gather_path_ms), bench::median(depth_ms), bench::median(composite_ms),
                layer_mb, ratio, identical ? "yes" : "NO"));
        }
    }
    note(fmt::format("load average (1, 5, 15 min) at the end: {}", bench::load_average()));
    if (csv)
        std::fclose(csv);
    // The frames of the two paths must be the same pixels.
    int failed = leader && !all_identical ? 1 : 0;
    MPI_Bcast(&failed, 1, MPI_INT, 0, MPI_COMM_WORLD);
    return failed;
}
