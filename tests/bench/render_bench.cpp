// Render benchmark: frames per second, milliseconds and CPU milliseconds per
// 1280x720 frame by backend, sphere technique, particle count (10k, 100k, 1M)
// and layout: a cube of fluid on a lattice seen whole, the same cube seen
// from close by (about half of its surface outside the view), and particles
// scattered at random in the same box (a gas: none buried). A program that
// prints a table, not a timed test. The techniques of one case take turns
// frame by frame, so a change in the load of a shared machine touches them
// alike; each row also gives how far its frame is from the plain ray-cast
// one's (sphclip compare's metrics), as speed must not cost the look. Rows
// the renderer cannot draw (flat discs, sorting, conservative depth) are
// drawn by the benchmark's own variants (render_variants.hpp), built from
// the renderer's parts.
//
//   build/sphclip_bench_render                       # the full table
//   build/sphclip_bench_render --csv FILE            # ... also to FILE, machine noted
//   build/sphclip_bench_render --png FOLDER          # ... and each row's frame
//   build/sphclip_bench_render --counts 1000000 --backends egl   # a part of it
//   build/sphclip_bench_render --tiny                # one small frame per case (CI)
//   build/sphclip_bench_render --light --size 1920x1080   # light and depth's rows only
//   build/sphclip_bench_render --parts --counts 100000     # ... each split into its parts
#include "bench_particles.hpp"
#include "bench_support.hpp"
#include "output/image_compare.hpp"
#include "output/png_io.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "render_variants.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

using namespace sph;

namespace {

// A way to draw the spheres: each row differs from "ray-cast" (every sphere
// a ray-cast impostor on a square) in what it names; "default" takes
// RenderSettings' defaults instead.
struct Technique {
    const char* name;
    SphereDrawing spheres = SphereDrawing::impostor;
    bool skip_buried = true;
    bool cull_view = true;
    double flat_below_px = 0;
    bool flat_as_points = false;
    bool sort = false;
    bool conservative_depth = false;
    double triangles_below_px = 0; // 0: squares only
    int samples = 4;
    bool defaults = false;
    // Light and depth: off in the sphere techniques' rows (they compare the
    // spheres alone), on in the rows named for them and in "default".
    bool shadows = false;
    bool ambient_occlusion = false;
    bool light_row = false; // one of light and depth's rows (--light)
};

// The benchmark's own part of a technique: none for the renderer's.
DrawVariant variant_of(const Technique& t) {
    return {.flat_below_px = t.flat_below_px,
            .flat_as_points = t.flat_as_points,
            .sort_front_to_back = t.sort,
            .conservative_depth = t.conservative_depth};
}

bool is_plain(const DrawVariant& v) {
    return v.flat_below_px <= 0 && !v.sort_front_to_back && !v.conservative_depth;
}

// One technique's renderer (the product's, or a variant of it) and the
// frames it drew.
struct Row {
    const Technique* technique;
    DrawVariant variant;
    std::unique_ptr<FrameRenderer> renderer;           // plain techniques
    std::unique_ptr<VariantRenderer> variant_renderer; // the others
    std::vector<double> ms, cpu_ms, fill_ms, draw_ms, readback_ms;
    std::array<std::vector<double>, frame_part_count> part_ms; // --parts
    Image image;                                               // the last frame

    Row(const Technique& t, const RenderSettings& r) : technique(&t), variant(variant_of(t)) {
        if (is_plain(variant))
            renderer = std::make_unique<FrameRenderer>(r);
        else
            variant_renderer = std::make_unique<VariantRenderer>(r, variant);
    }
    Image render(const Snapshot& s) {
        return renderer ? renderer->render(s) : variant_renderer->render(s);
    }
    const FrameTimings& timings() const {
        return renderer ? renderer->last_timings() : variant_renderer->last_timings();
    }
    const RenderSettings& settings() const {
        return renderer ? renderer->settings() : variant_renderer->settings();
    }
    std::size_t drawn() const {
        return renderer ? renderer->last_drawn() : variant_renderer->last_drawn();
    }
    std::size_t flat() const { return renderer ? 0 : variant_renderer->last_flat(); }
    std::size_t outside_view() const {
        return renderer ? renderer->last_outside_view() : variant_renderer->last_outside_view();
    }
};

// How the impostors' outlines are chosen.
std::string outline_name(const RenderSettings& r) {
    if (r.spheres != SphereDrawing::impostor)
        return "";
    if (r.triangles_below_px <= 0)
        return "square";
    if (r.triangles_below_px > 1e6)
        return "triangle";
    return fmt::format("triangle below {:g} px", r.triangles_below_px);
}

} // namespace

int main(int argc, char** argv) {
    bench::CommonOptions options;
    const bool& tiny = options.tiny;
    const std::string &csv_path = options.csv, &png_folder = options.png;
    bool light_only = false;
    // --parts: light and depth's rows, each frame's parts timed on their
    // own (FrameRenderer::time_parts), a row of their times instead of the
    // usual row.
    bool parts = false;
    int size_w = 0, size_h = 0;
    for (int k = 1; k < argc; ++k) {
        const std::string arg = argv[k];
        if (options.take(k, argc, argv))
            continue;
        if (arg == "--light")
            light_only = true;
        else if (arg == "--parts")
            light_only = parts = true;
        else if (arg == "--size" && k + 1 < argc &&
                 std::sscanf(argv[++k], "%dx%d", &size_w, &size_h) == 2 && size_w > 0 &&
                 size_h > 0) {
        } else {
            fmt::print(stderr,
                       "usage: {} [--tiny] [--counts N,N] [--backends egl,osmesa] [--csv FILE] "
                       "[--png FOLDER] [--light] [--parts] [--size WxH]\n",
                       argv[0]);
            return 2;
        }
    }
    std::FILE* csv = csv_path.empty() ? nullptr : std::fopen(csv_path.c_str(), "w");
    if (!csv_path.empty() && !csv) {
        fmt::print(stderr, "cannot write {}\n", csv_path);
        return 2;
    }
    auto emit = [csv](const std::string& line) {
        fmt::print("{}\n", line);
        std::fflush(stdout);
        if (csv) {
            fmt::print(csv, "{}\n", line);
            std::fflush(csv);
        }
    };
    if (!png_folder.empty())
        std::filesystem::create_directories(png_folder);

    const int width = size_w > 0 ? size_w : tiny ? 320 : 1280;
    const int height = size_h > 0 ? size_h : tiny ? 180 : 720;
    const std::vector<std::size_t> counts = options.particle_counts(
        tiny ? std::vector<std::size_t>{1000} : std::vector<std::size_t>{10000, 100000, 1000000});
    const std::vector<std::string> backends = bench::split_list(options.backends);
    // The machine, in the CSV's header: these figures mean little without it.
    auto note = [csv](const std::string& line) {
        if (csv)
            fmt::print(csv, "# {}\n", line);
    };
    {
        note(fmt::format("sphclip_bench_render, {}", bench::now_utc()));
        note(fmt::format("{} cores (nproc), {}", std::thread::hardware_concurrency(),
                         bench::cpu_model()));
        auto context = make_gl_context(backends.empty() ? "auto" : backends.front());
        note(fmt::format("{}, OpenGL {}", context->info().renderer, context->info().version));
        note(fmt::format("load average (1, 5, 15 min) at the start: {}", bench::load_average()));
    }
    // Every sphere ray-cast on a square first (the renderer before triangles,
    // culling and flat discs): the others' frames are compared with its.
    // "default" is RenderSettings' defaults: small spheres on triangles.
    const std::vector<Technique> techniques = {
        {.name = "ray-cast"},
        {.name = "view culling off", .cull_view = false},
        {.name = "conservative depth", .conservative_depth = true},
        {.name = "ray-cast triangles", .triangles_below_px = 1e9},
        {.name = "no multisampling", .samples = 0},
        {.name = "sorted ray-cast", .sort = true},
        {.name = "flat quads < 4 px", .flat_below_px = 4},
        {.name = "flat points < 4 px", .flat_below_px = 4, .flat_as_points = true},
        {.name = "flat quads < 8 px", .flat_below_px = 8},
        {.name = "all flat quads", .flat_below_px = 1e9},
        {.name = "all flat quads sorted", .flat_below_px = 1e9, .sort = true},
        {.name = "all flat points", .flat_below_px = 1e9, .flat_as_points = true},
        {.name = "default", .defaults = true, .light_row = true},
        {.name = "shadows", .shadows = true, .light_row = true},
        {.name = "ambient occlusion", .ambient_occlusion = true, .light_row = true},
        {.name = "shadows and ambient occlusion",
         .shadows = true,
         .ambient_occlusion = true,
         .light_row = true},
        {.name = "seed: mesh",
         .spheres = SphereDrawing::mesh,
         .skip_buried = false,
         .cull_view = false},
        {.name = "mesh", .spheres = SphereDrawing::mesh},
    };

    if (parts) {
        std::string header = "backend,layout,particles,technique,drawn,width,height,ms_per_frame";
        for (std::size_t k = 0; k < frame_part_count; ++k)
            header += fmt::format(",{}_ms", frame_part_name(FramePart(k)));
        emit(header);
    } else {
        emit("backend,layout,particles,technique,spheres,skip_buried,cull_view,flat_below_px,"
             "flat_as,sorted,outline,samples,drawn,flat,outside_view,width,height,"
             "shadows,ambient_occlusion,ms_per_frame,fps,cpu_ms,fill_ms,draw_ms,readback_ms,"
             "mean_diff_vs_raycast,different_pct_vs_raycast,match_vs_raycast,resident_mb");
    }
    const char* layouts[] = {"block", "close-up", "scattered"};
    for (std::size_t n : counts)
        for (const char* layout : layouts) {
            const bool block = std::strcmp(layout, "scattered") != 0;
            const bool close_up = std::strcmp(layout, "close-up") == 0;
            // The spacing shrinks with the count in a fixed 0.1 m box: the
            // block's spheres are ~8 px across at 100k, ~4 px at 1M.
            const double box = 0.1, spacing = box / std::ceil(std::cbrt(double(n)));
            const Snapshot s = bench::make_particles(n, block, spacing, box);
            for (const std::string& backend : backends) {
                auto context = make_gl_context(backend);
                std::vector<Row> rows;
                for (const Technique& t : techniques) {
                    const bool is_reference = &t == &techniques.front();
                    const bool is_default = t.defaults;
                    const bool mesh = t.spheres == SphereDrawing::mesh;
                    // What each layout is for: every technique on the whole
                    // block and the gas; culling on the close-up. Meshes
                    // (the seed's 80 triangles a sphere) stop at 100k.
                    const bool culling_row = std::strcmp(t.name, "view culling off") == 0;
                    if (close_up ? !(is_reference || is_default || culling_row) : culling_row)
                        continue;
                    if (mesh && (n > 100000 || !block))
                        continue;
                    if (light_only && !is_reference && !t.light_row)
                        continue;
                    if (parts && !t.light_row)
                        continue;
                    if (t.light_row && !t.defaults && close_up)
                        continue;
                    if (tiny && !is_reference && !is_default && !mesh && t.flat_below_px != 4 &&
                        t.cull_view)
                        continue;
                    RenderSettings r;
                    r.width = width;
                    r.height = height;
                    r.dimension = 3;
                    r.spheres = t.spheres;
                    r.radius = 0.5 * spacing;
                    r.range = {0, 2};
                    r.domain_min = glm::dvec3(0);
                    r.domain_max = glm::dvec3(box);
                    r.cull_buried = block && t.skip_buried;
                    if (!t.defaults) {
                        r.shadows = t.shadows;
                        r.ambient_occlusion = t.ambient_occlusion;
                        r.cull_outside_view = t.cull_view;
                        r.triangles_below_px = t.triangles_below_px;
                        r.samples = t.samples;
                    }
                    if (close_up) {
                        // Looking into the block past a corner: ~2/3 of its
                        // surface is outside the view.
                        r.camera_target = glm::dvec3(0.075, 0.07, 0.07);
                        r.camera_position =
                            r.camera_target + 0.07 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
                    } else {
                        // The whole box in view but for the block's nearest
                        // bottom corner.
                        r.camera_target = glm::dvec3(0.05);
                        r.camera_position =
                            glm::dvec3(0.05) + 0.2 * glm::normalize(glm::dvec3(0.8, 0.6, 1.3));
                    }
                    rows.emplace_back(t, r);
                    if (parts)
                        rows.back().renderer->time_parts(true);
                    rows.back().render(s); // warm-up: shader compilation, buffers
                }
                // Round-robin over the techniques, so that a change in the load
                // of this shared machine touches all of them alike; the median
                // of each technique's frames.
                double round_seconds = 0;
                for (const Row& row : rows)
                    round_seconds += row.timings().draw_seconds;
                const int rounds = tiny ? 1 : round_seconds > 20 ? 3 : 5;
                for (int round = 0; round < rounds; ++round)
                    for (Row& row : rows) {
                        const auto start = std::chrono::steady_clock::now();
                        const double cpu_start = bench::cpu_ms();
                        row.image = row.render(s);
                        row.ms.push_back(std::chrono::duration<double, std::milli>(
                                             std::chrono::steady_clock::now() - start)
                                             .count());
                        row.cpu_ms.push_back(bench::cpu_ms() - cpu_start);
                        const FrameTimings& ft = row.timings();
                        row.fill_ms.push_back(ft.fill_seconds * 1e3);
                        row.draw_ms.push_back(ft.draw_seconds * 1e3);
                        row.readback_ms.push_back(ft.readback_seconds * 1e3);
                        for (std::size_t k = 0; k < frame_part_count; ++k)
                            row.part_ms[k].push_back(ft.part_seconds[k] * 1e3);
                    }
                if (parts) {
                    for (Row& row : rows) {
                        std::string line = fmt::format("{},{},{},{},{},{},{},{:.1f}", backend,
                                                       layout, n, row.technique->name, row.drawn(),
                                                       width, height, bench::median(row.ms));
                        for (std::size_t k = 0; k < frame_part_count; ++k)
                            line += fmt::format(",{:.1f}", bench::median(row.part_ms[k]));
                        emit(line);
                    }
                    continue;
                }
                const Image& reference = rows.front().image;
                for (Row& row : rows) {
                    const Technique& t = *row.technique;
                    const RenderSettings& r = row.settings();
                    const DrawVariant& v = row.variant;
                    std::string versus = ",,";
                    if (&row != &rows.front()) {
                        const CompareResult c =
                            compare_images(reference, row.image, CompareOptions{});
                        versus = fmt::format("{:.2f},{:.2f},{}", c.mean_difference,
                                             c.different_percent, c.match ? "yes" : "no");
                    }
                    const bool flat = v.flat_below_px > 0 && r.spheres == SphereDrawing::impostor;
                    const double ms = bench::median(row.ms);
                    emit(fmt::format(
                        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.1f},{:.2f},{:."
                        "1f},"
                        "{:.1f},{:.1f},{:.1f},{},{:.0f}",
                        backend, layout, n, t.name, choice_name(t.spheres),
                        r.cull_buried ? "yes" : "no", r.cull_outside_view ? "yes" : "no",
                        flat ? fmt::format("{:g}", v.flat_below_px) : "",
                        flat ? (v.flat_as_points ? "points" : "quads") : "",
                        v.sort_front_to_back ? "yes" : "no", outline_name(r), r.samples,
                        row.drawn(), row.flat(), row.outside_view(), width, height,
                        r.shadows && r.dimension == 3 ? "on" : "off",
                        r.ambient_occlusion && r.dimension == 3 ? "on" : "off", ms, 1e3 / ms,
                        bench::median(row.cpu_ms), bench::median(row.fill_ms),
                        bench::median(row.draw_ms), bench::median(row.readback_ms), versus,
                        bench::status_bytes("VmRSS") / (1024.0 * 1024.0)));
                    if (!png_folder.empty()) {
                        std::string name = fmt::format("{}_{}_{}_{}", backend, layout, n, t.name);
                        for (char& c : name)
                            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_')
                                c = '-';
                        write_png(std::filesystem::path(png_folder) / (name + ".png"), row.image);
                    }
                }
            }
        }
    note(fmt::format("load average (1, 5, 15 min) at the end: {}", bench::load_average()));
    if (csv)
        std::fclose(csv);
    return 0;
}
