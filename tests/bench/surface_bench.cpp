// Surface benchmark (render.style = surface): milliseconds per frame split
// into the reconstruction (particles to level set to mesh, OpenVDB, on the
// CPU), colouring the vertices, and drawing (upload, GL draw, overlay and
// read-back), by backend, particle count (10k, 100k, 1M) and frame size
// (1280x720, 1920x1080), with the mesh's size and the process's peak memory.
// The fluid: a cube of particles on a jittered lattice with 2% of them as
// spray above it, in a 0.1 m box, the spacing shrinking with the count as in
// the render benchmark. A program that prints a table, not a timed test.
//
//   build/sphclip_bench_surface                  # the full table
//   build/sphclip_bench_surface --csv FILE       # ... also to FILE, machine noted
//   build/sphclip_bench_surface --png FOLDER     # ... and each row's frame
//   build/sphclip_bench_surface --counts 100000 --backends egl
//   build/sphclip_bench_surface --tiny           # one small frame (CI)
//   build/sphclip_bench_surface --light          # ... also with shadows and/or ambient occlusion
//   build/sphclip_bench_surface --parts          # ... the frame's drawing split into its parts
#include "bench_support.hpp"
#include "output/png_io.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "render/surface/reconstruct.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <random>
#include <string>
#include <sys/resource.h>
#include <thread>
#include <vector>

using namespace sph;

namespace {

using Clock = std::chrono::steady_clock;

Snapshot make_fluid(std::size_t n, double spacing) {
    Snapshot s;
    s.dimension = 3;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    const std::size_t spray = n / 50, block = n - spray;
    const std::size_t side = std::size_t(std::ceil(std::cbrt(double(block))));
    for (std::size_t i = 0; i < n; ++i) {
        double p[3];
        if (i < block) {
            const std::size_t c[3] = {i % side, i / side % side, i / side / side};
            for (int a = 0; a < 3; ++a)
                p[a] = (double(c[a]) + 0.5 + 0.15 * u(rng)) * spacing;
        } else {
            // Drops above the block, a few spacings apart.
            const double top = double(side) * spacing;
            p[0] = (0.5 + 0.5 * u(rng)) * top;
            p[1] = top * (1.05 + 0.1 * (0.5 + 0.5 * u(rng)));
            p[2] = (0.5 + 0.5 * u(rng)) * top;
        }
        s.position.insert(s.position.end(), {p[0], p[1], p[2]});
        s.velocity.insert(s.velocity.end(), {20 * p[1], 0, 0});
        s.density.push_back(1000);
        s.pressure.push_back(0);
        s.id.push_back(std::uint32_t(i));
    }
    return s;
}

} // namespace

int main(int argc, char** argv) {
    bench::CommonOptions options;
    const bool& tiny = options.tiny;
    const std::string &csv_path = options.csv, &png_folder = options.png;
    int repeats = 3;
    bool light = false;
    // --parts: the frame's parts each timed on their own
    // (FrameRenderer::time_parts), a column each.
    bool parts = false;
    SurfaceSettings surface;
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        if (options.take(k, argc, argv))
            continue;
        if (arg == "--smoothing" && k + 1 < argc)
            surface.smoothing = std::stoi(argv[++k]);
        else if (arg == "--voxel" && k + 1 < argc)
            surface.voxel = std::stod(argv[++k]);
        else if (arg == "--light")
            light = true;
        else if (arg == "--parts")
            parts = true;
        else if (arg == "--repeats" && k + 1 < argc)
            repeats = std::max(1, std::stoi(argv[++k]));
        else {
            fmt::print(
                stderr,
                "usage: {} [--tiny] [--counts N,N] [--backends egl,osmesa] [--repeats N] "
                "[--smoothing N] [--voxel V] [--light] [--parts] [--csv FILE] [--png FOLDER]\n",
                argv[0]);
            return 2;
        }
    }
    if (!surface_3d_available()) {
        fmt::print("this build has no OpenVDB: no 3D surface to measure\n");
        return 0;
    }
    std::FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
    auto emit = [csv](const std::string& line) {
        fmt::print("{}\n", line);
        if (csv) {
            fmt::print(csv, "{}\n", line);
            std::fflush(csv);
        }
    };
    auto note = [&](const std::string& line) {
        fmt::print("# {}\n", line);
        if (csv)
            fmt::print(csv, "# {}\n", line);
    };
    if (!png_folder.empty())
        std::filesystem::create_directories(png_folder);
    const std::vector<std::size_t> counts = options.particle_counts(
        tiny ? std::vector<std::size_t>{2000} : std::vector<std::size_t>{10000, 100000, 1000000});
    const std::vector<std::array<int, 2>> sizes =
        tiny ? std::vector<std::array<int, 2>>{{320, 180}}
             : std::vector<std::array<int, 2>>{{1280, 720}, {1920, 1080}};
    if (tiny)
        repeats = 1;
    {
        note(fmt::format("sphclip_bench_surface, {}", bench::now_utc()));
        note(fmt::format("{} cores (nproc), {}", std::thread::hardware_concurrency(),
                         bench::cpu_model()));
        note(fmt::format("load average (1, 5, 15 min) at the start: {}", bench::load_average()));
        note(fmt::format("render.surface: voxel {}, radius {} (x spacing), smoothing {}",
                         surface.voxel, surface.radius, surface.smoothing));
    }
    // The reconstruction's steps after the first columns, and its CPU time
    // (OpenVDB's threads included): how many cores it keeps busy.
    std::string header =
        "backend,particles,width,height,vertices,triangles,reconstruct_ms,colour_ms,"
        "draw_ms,readback_ms,frame_ms,peak_rss_mib,shadows,ambient_occlusion,"
        "rasterise_ms,smoothing_ms,meshing_ms,normals_ms,reconstruct_cpu_ms";
    if (parts)
        for (std::size_t k = 0; k < frame_part_count; ++k)
            header += fmt::format(",{}_ms", frame_part_name(FramePart(k)));
    emit(header);
    // Light and depth's switches (render.shadows, render.ambient_occlusion):
    // off, as by default; with --light each on alone and both.
    std::vector<std::array<bool, 2>> lights{{false, false}};
    if (light)
        lights.insert(lights.end(), {{true, false}, {false, true}, {true, true}});
    const std::vector<std::string> backends = bench::split_list(options.backends);
    for (std::size_t n : counts) {
        const double box = 0.1, spacing = box / std::ceil(std::cbrt(double(n)));
        Snapshot frame = make_fluid(n, spacing);
        for (const std::string& backend : backends) {
            auto context = make_gl_context(backend);
            for (const auto& [width, height] : sizes)
                for (const auto& [shadows, occlusion] : lights) {
                    RenderSettings r;
                    r.shadows = shadows;
                    r.ambient_occlusion = occlusion;
                    r.width = width;
                    r.height = height;
                    r.dimension = 3;
                    r.style = FluidStyle::surface;
                    r.surface = surface;
                    r.spacing = spacing;
                    r.radius = 0.5 * spacing;
                    r.range = {0, 2};
                    r.domain_min = glm::dvec3(0);
                    r.domain_max = glm::dvec3(box);
                    r.camera_target = glm::dvec3(0.05);
                    r.camera_position =
                        glm::dvec3(0.05) + 0.2 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
                    FrameRenderer renderer(r);
                    renderer.time_parts(parts);
                    std::vector<double> reconstruct, colour, draw, readback, total;
                    std::vector<double> rasterise, smoothing, meshing, normals, cpu;
                    std::array<std::vector<double>, frame_part_count> part_ms;
                    std::size_t vertices = 0, triangles = 0;
                    Image image;
                    for (int k = 0; k < repeats; ++k) {
                        // A new frame each time: the renderer reconstructs a
                        // frame's surface once (FrameSurface), and would reuse it.
                        frame.frame = std::uint64_t(k);
                        // The split, from the reconstruction alone...
                        const double cpu_start = bench::cpu_ms();
                        const Surface s = reconstruct_surface(frame, r.field, spacing, r.surface);
                        cpu.push_back(bench::cpu_ms() - cpu_start);
                        reconstruct.push_back(1e3 * s.reconstruction_seconds);
                        rasterise.push_back(1e3 * s.steps.rasterise);
                        smoothing.push_back(1e3 * s.steps.smoothing);
                        meshing.push_back(1e3 * s.steps.meshing);
                        normals.push_back(1e3 * s.steps.normals);
                        colour.push_back(1e3 * s.colour_seconds);
                        vertices = s.mesh.vertices();
                        triangles = s.mesh.triangles.size() / 3;
                        // ... and the whole frame as a run draws it.
                        const auto start = Clock::now();
                        image = renderer.render(frame);
                        total.push_back(
                            1e3 * std::chrono::duration<double>(Clock::now() - start).count());
                        const FrameTimings& t = renderer.last_timings();
                        draw.push_back(1e3 * (t.draw_seconds - t.surface_seconds));
                        readback.push_back(1e3 * t.readback_seconds);
                        for (std::size_t p = 0; p < frame_part_count; ++p)
                            part_ms[p].push_back(1e3 * t.part_seconds[p]);
                    }
                    std::string line = fmt::format(
                        "{},{},{},{},{},{},{:.1f},{:.1f},{:.1f},{:.1f},{:.1f},{:.0f},{},{},{:.1f},{"
                        ":"
                        ".1f},{:.1f},{:.1f},{:.1f}",
                        backend, n, width, height, vertices, triangles, bench::median(reconstruct),
                        bench::median(colour), bench::median(draw), bench::median(readback),
                        bench::median(total), bench::peak_rss_mib(), shadows ? "on" : "off",
                        occlusion ? "on" : "off", bench::median(rasterise),
                        bench::median(smoothing), bench::median(meshing), bench::median(normals),
                        bench::median(cpu));
                    if (parts)
                        for (std::size_t p = 0; p < frame_part_count; ++p)
                            line += fmt::format(",{:.1f}", bench::median(part_ms[p]));
                    emit(line);
                    if (!png_folder.empty())
                        write_png(std::filesystem::path(png_folder) /
                                      fmt::format("surface_{}_{}_{}x{}{}{}.png", backend, n, width,
                                                  height, shadows ? "_shadows" : "",
                                                  occlusion ? "_ao" : ""),
                                  image);
                }
        }
    }
    note(fmt::format("load average (1, 5, 15 min) at the end: {}", bench::load_average()));
    if (csv)
        std::fclose(csv);
    return 0;
}
