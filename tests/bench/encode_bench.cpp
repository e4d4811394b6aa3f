// Encode benchmark: frames per second and file size of the MP4 encoder
// (colour conversion, libx264, muxing: src/output/mp4_writer) by frame size, x264
// preset and x264 thread count, on the frames of the built-in scene (the 2D
// dam break, simulated and rendered once, then encoded again and again). A
// program that prints a table, not a timed test; the run's defaults come
// from its results (docs/rendering.md, "What encoding costs"; the tables
// are in docs/benchmarks.md).
//
//   build/sphclip_bench_encode                      # the full table
//   build/sphclip_bench_encode --repeat 5 --csv F   # also written to F
//   build/sphclip_bench_encode --tiny               # one small case (CI)
#include "bench_support.hpp"
#include "output/mp4_writer.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "scene/scene_setup.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <string>
#include <unistd.h>
#include <vector>

using namespace sph;
namespace fs = std::filesystem;

namespace {

struct Options {
    bool tiny = false;
    int repeat = 5;
    std::string csv;
};

// The built-in scene's frames as a run takes them: at k / fps.
std::vector<Snapshot> simulate_frames(const Scene& scene) {
    auto sim = make_simulation<2>(scene);
    const auto frames = std::uint64_t(std::floor(scene.duration * scene.fps + 1e-9)) + 1;
    std::vector<Snapshot> snapshots;
    for (std::uint64_t k = 0; k < frames; ++k) {
        const double t = double(k) / scene.fps;
        while (!sim.reached(t))
            sim.step_toward(t);
        sim.update_fields();
        Snapshot s;
        s.frame = k;
        s.steps = sim.steps();
        s.time = sim.time();
        s.stats = measure_frame(sim.params(), sim.state());
        copy_fields(sim.state(), s);
        snapshots.push_back(std::move(s));
    }
    return snapshots;
}

std::vector<Image> render_frames(Scene scene, const std::vector<Snapshot>& snapshots, int width,
                                 int height) {
    scene.render.size = {width, height};
    FrameRenderer renderer(make_render_settings(scene));
    std::vector<Image> images;
    for (const auto& s : snapshots)
        images.push_back(renderer.render(s));
    return images;
}

std::uint64_t fnv1a(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::uint64_t hash = 1469598103934665603ull;
    for (std::istreambuf_iterator<char> it(in), end; it != end; ++it)
        hash = (hash ^ std::uint8_t(*it)) * 1099511628211ull;
    return hash;
}

// One setting's repeats.
struct Measured {
    std::vector<double> rates; // frames per second
    std::uintmax_t bytes = 0;
    std::uint64_t hash = 0;
    bool same_bytes = true; // every repeat wrote the same file

    double median() const {
        std::vector<double> sorted = rates;
        std::sort(sorted.begin(), sorted.end());
        return sorted[sorted.size() / 2];
    }
};

void encode(const std::vector<Image>& frames, double fps, const Mp4Options& options,
            const fs::path& file, Measured& m) {
    const auto start = std::chrono::steady_clock::now();
    {
        Mp4Writer writer(file, frames.front().width, frames.front().height, fps, options);
        for (const auto& frame : frames)
            writer.write(frame);
        writer.finish();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::uint64_t hash = fnv1a(file);
    if (m.rates.empty()) {
        m.hash = hash;
        m.bytes = fs::file_size(file);
    } else if (hash != m.hash) {
        m.same_bytes = false;
    }
    m.rates.push_back(double(frames.size()) / seconds);
    fs::remove(file);
}

} // namespace

int main(int argc, char** argv) {
    Options options;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--tiny") == 0)
            options.tiny = true;
        else if (std::strcmp(argv[i], "--repeat") == 0 && i + 1 < argc)
            options.repeat = std::max(1, std::atoi(argv[++i]));
        else if (std::strcmp(argv[i], "--csv") == 0 && i + 1 < argc)
            options.csv = argv[++i];
        else {
            std::fprintf(stderr, "usage: %s [--tiny] [--repeat N] [--csv FILE]\n", argv[0]);
            return 2;
        }
    }
    if (options.tiny)
        options.repeat = 1;

    // The built-in scene (31 frames); --tiny: a coarse one of 3 frames.
    std::vector<Override> overrides;
    if (options.tiny)
        overrides = {{"duration", "0.1"}, {"fps", "20"}, {"fluid.spacing", "0.01"}};
    const Scene scene = default_scene(overrides);
    const std::vector<Snapshot> snapshots = simulate_frames(scene);

    using Size = std::pair<int, int>;
    const std::vector<Size> sizes =
        options.tiny ? std::vector<Size>{{320, 180}} : std::vector<Size>{{1280, 720}, {1920, 1080}};
    const std::vector<std::string> presets =
        options.tiny
            ? std::vector<std::string>{"ultrafast"}
            : std::vector<std::string>{"ultrafast", "superfast", "veryfast", "faster", "medium"};
    const std::vector<int> thread_counts =
        options.tiny ? std::vector<int>{1} : std::vector<int>{1, 2, 0};

    std::string table = fmt::format(
        "# sphclip_bench_encode: {} cores (nproc), {}; libx264 CRF 20, {} frames of the built-in "
        "scene at {} fps; median of {} repeats\n"
        "# threads: x264 threads, 0 = libx264's choice (auto); mb_tree: x264's macroblock tree "
        "(off in sphclip); same_bytes: every repeat wrote the same file\n"
        "width,height,preset,threads,mb_tree,frames,fps_median,fps_min,fps_max,ms_per_frame,"
        "bytes,same_bytes\n",
        sysconf(_SC_NPROCESSORS_ONLN), bench::cpu_model(), snapshots.size(), scene.fps,
        options.repeat);
    std::fputs(table.c_str(), stdout);
    std::fflush(stdout);

    auto context = make_gl_context("auto");
    const fs::path file =
        fs::temp_directory_path() / fmt::format("sphclip_bench_encode_{}.mp4", getpid());
    for (const auto& [width, height] : sizes) {
        const std::vector<Image> frames = render_frames(scene, snapshots, width, height);
        std::vector<Mp4Options> settings;
        for (const auto& preset : presets)
            for (int threads : thread_counts)
                settings.push_back({20, preset, threads, false});
        // The price of determinism: the macroblock tree on, where a preset uses it.
        if (!options.tiny)
            for (const char* preset : {"veryfast", "faster", "medium"})
                for (int threads : {1, 0})
                    settings.push_back({20, preset, threads, true});
        // Repeats go round all settings in turn, so that a burst of load on
        // the (shared) machine slows every setting alike, not one of them.
        std::vector<Measured> measured(settings.size());
        for (int r = 0; r < options.repeat; ++r)
            for (std::size_t i = 0; i < settings.size(); ++i)
                encode(frames, scene.fps, settings[i], file, measured[i]);
        for (std::size_t i = 0; i < settings.size(); ++i) {
            const Mp4Options& mp4 = settings[i];
            const Measured& m = measured[i];
            const auto [low, high] = std::minmax_element(m.rates.begin(), m.rates.end());
            const std::string row = fmt::format(
                "{},{},{},{},{},{},{:.1f},{:.1f},{:.1f},{:.1f},{},{}\n", width, height, mp4.preset,
                mp4.threads, mp4.mb_tree ? "on" : "off", frames.size(), m.median(), *low, *high,
                1e3 / m.median(), m.bytes, m.same_bytes ? "yes" : "no");
            std::fputs(row.c_str(), stdout);
            std::fflush(stdout);
            table += row;
        }
    }
    if (!options.csv.empty())
        std::ofstream(options.csv) << table;
    return 0;
}
