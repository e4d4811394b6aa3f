#include "cli/run_command.hpp"

#include "cli/exit_codes.hpp"
#include "cli/progress.hpp"
#include "cli/stage_report.hpp"
#include "io/files.hpp"
#include "io/input_error.hpp"
#include "io/particle_export.hpp"
#include "io/scene_setup.hpp"
#include "io/stats_csv.hpp"
#include "render/render_sink.hpp"
#include "sph/surface.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <exception>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <optional>
#include <unistd.h>
#include <vector>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::atomic<int> interrupt_signal{0};

extern "C" void on_interrupt(int signal) {
    interrupt_signal.store(signal);
}

// Stops simulating on SIGINT/SIGTERM; the outputs so far are finalised.
struct InterruptGuard {
    InterruptGuard() {
        interrupt_signal.store(0);
        previous_int_ = std::signal(SIGINT, on_interrupt);
        previous_term_ = std::signal(SIGTERM, on_interrupt);
    }
    ~InterruptGuard() {
        std::signal(SIGINT, previous_int_);
        std::signal(SIGTERM, previous_term_);
    }
    void (*previous_int_)(int);
    void (*previous_term_)(int);
};

// Creates the output folder and checks it can be written, before anything is
// written to it.
void prepare_output_folder(const fs::path& folder) {
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec || !fs::is_directory(folder))
        throw InputError("command line", "--out",
                         fmt::format("cannot create the output folder {}: {}", folder.string(),
                                     ec ? ec.message() : "a file of that name exists"));
    if (access(folder.c_str(), W_OK | X_OK) != 0)
        throw InputError("command line", "--out",
                         fmt::format("the output folder {} is not writable", folder.string()));
}

// Frames of an earlier run in the same folder would mix with this run's.
void remove_earlier_frames(const fs::path& folder) {
    std::error_code ec;
    for (const char* sub : {"particles", "frames"})
        for (const auto& entry : fs::directory_iterator(folder / sub, ec)) {
            const auto name = entry.path().filename().string();
            const auto ext = entry.path().extension().string();
            if (name.starts_with("frame_") && (ext == ".csv" || ext == ".vtp" || ext == ".png"))
                fs::remove(entry.path(), ec);
        }
    fs::remove(folder / "particles.pvd", ec);
}

struct RunRecord {
    json document;
    fs::path path;
    void save(const std::string& status, std::uint64_t frames, std::uint64_t steps,
              double simulated, double wall, const std::string& error = {}) {
        document["status"] = status;
        document["frames"] = frames;
        document["steps"] = steps;
        document["simulated_time"] = simulated;
        document["wall_s"] = wall;
        if (!error.empty())
            document["error"] = error;
        write_file_atomically(path, document.dump(2) + "\n");
    }
};

// One x264 thread, by measurement (tests/bench/results/encode.csv, README
// "What encoding costs"): on 2 busy cores it encodes fastest, it leaves the
// other core to the simulation while it overlaps it, and the clip's bytes do
// not depend on the machine's core count, as libx264's choice would.
constexpr int encoder_threads = 1;

// Half the size, rounded to even (yuv420p needs even sizes, so the video is
// not padded), and libx264's fastest preset. run.json's scene records both.
void make_fast_preview(Scene& scene) {
    for (int& side : scene.render.size)
        side = 2 * std::max(1, (side + 2) / 4);
    scene.render.video_preset = "ultrafast";
}

template <int D>
int run_clip(const Scene& scene, const fs::path& folder, const RunOptions& options,
             std::unique_ptr<GlContext> gl_context) {
    const Derived derived = derive(scene);
    Simulation<D> sim = make_simulation<D>(scene, derived);
    const std::uint64_t frames =
        static_cast<std::uint64_t>(std::floor(scene.duration * scene.fps + 1e-9)) + 1;

    RenderSink* render = nullptr;
    std::unique_ptr<RenderSink> render_sink;
    if (gl_context) {
        render_sink = std::make_unique<RenderSink>(
            std::move(gl_context), make_render_settings(scene),
            options.png ? folder / "frames" : fs::path(),
            options.mp4 ? folder / "clip.mp4" : fs::path(), scene.fps,
            Mp4Options{scene.render.video_quality, scene.render.video_preset, encoder_threads},
            EncodeThread::worker);
        render = render_sink.get();
    }

    std::vector<std::unique_ptr<FrameSink>> sinks;
    sinks.push_back(std::make_unique<StatsCsv>(folder / "stats.csv"));
    for (const auto& format : options.exports) {
        fs::create_directories(folder / "particles");
        if (format == "csv")
            sinks.push_back(std::make_unique<ParticleCsv>(folder));
        else if (format == "vtk")
            sinks.push_back(std::make_unique<ParticleVtk>(folder));
    }
    if (render_sink)
        sinks.push_back(std::move(render_sink));
    // Only the fields some sink reads are computed for output and copied.
    FrameFields fields{.pressure = false};
    for (const auto& sink : sinks)
        fields |= sink->fields();
    sim.set_output_fields(fields);

    RunRecord record;
    record.path = folder / "run.json";
    record.document = {
        {"sphclip_version", SPHCLIP_VERSION},
        {"command", options.command_line},
        {"scene_file", scene.file},
        {"scene", to_json(scene)},
        {"derived",
         {{"smoothing_length", derived.h},
          {"mass", derived.mass},
          {"dt", derived.dt},
          {"sound_speed", derived.sound_speed},
          {"max_speed", sim.params().watchdog.max_speed}}},
        {"particles", sim.state().size()},
        {"threads", omp_get_max_threads()},
        {"solver", std::string(sim.solver().name())},
        {"neighbour_search", std::string(sim.search().name())},
        {"fast_preview", options.fast_preview},
        {"outputs",
         {{"stats", "stats.csv"},
          {"exports", options.exports},
          {"png", options.png ? json("frames/") : json(false)},
          {"mp4", options.mp4 ? json("clip.mp4") : json(false)}}},
        {"output_fields", {{"pressure", fields.pressure}}},
    };
    if (render)
        record.document["gl"] = {{"backend", render->gl_info().backend},
                                 {"vendor", render->gl_info().vendor},
                                 {"renderer", render->gl_info().renderer},
                                 {"version", render->gl_info().version}};
    record.save("running", 0, 0, 0, 0);

    if (!options.quiet) {
        fmt::print("sphclip: {} ({}D, {} solver): {} particles, h = {:.4g} m, m = {:.4g} kg, "
                   "dt = {:.4g} s, {} frames of {:.4g} s -> {}\n",
                   scene.name, D, scene.solver.name, sim.state().size(), derived.h, derived.mass,
                   derived.dt, frames, scene.duration, folder.string());
        if (options.fast_preview)
            fmt::print("sphclip: fast preview: half-size frames ({}x{}), x264 preset {}\n",
                       scene.render.size[0], scene.render.size[1], scene.render.video_preset);
        if (render)
            fmt::print("sphclip: rendering {}x{} with {} ({}, OpenGL {})\n", scene.render.size[0],
                       scene.render.size[1], render->gl_info().backend, render->gl_info().renderer,
                       render->gl_info().version);
    }

    Progress progress(!options.quiet && isatty(STDOUT_FILENO));
    InterruptGuard interrupt_guard;
    const auto start = std::chrono::steady_clock::now();
    auto wall = [&start] {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    // Every sink is finished, even after one fails (so the video is
    // finalised whatever happens); the first error is rethrown.
    auto finish_sinks = [&sinks] {
        std::exception_ptr error;
        for (auto& sink : sinks) {
            try {
                sink->finish();
            } catch (...) {
                if (!error)
                    error = std::current_exception();
            }
        }
        if (error)
            std::rethrow_exception(error);
    };

    Snapshot snapshot;
    std::uint64_t written = 0;
    // Stages outside the simulation step, for run.json "stages".
    double frame_fields_s = 0, sinks_s = 0;
    std::vector<double> simulate_seconds;
    std::vector<StageRow> stage_report;
    // Per frame: where the time went (run.json "timings").
    // The MP4 encoder runs on a worker thread: its busy time (`encode`)
    // overlaps the main thread's stages, and only the main thread's wait for
    // it (`encode wait`) adds to the wall time.
    auto record_timings = [&] {
        const std::vector<FrameCost> costs = render ? render->costs() : std::vector<FrameCost>{};
        json frames = json::array();
        double simulate_total = 0;
        FrameCost total;
        for (std::size_t k = 0; k < simulate_seconds.size(); ++k) {
            const FrameCost cost = k < costs.size() ? costs[k] : FrameCost{};
            simulate_total += simulate_seconds[k];
            total.render_s += cost.render_s;
            total.readback_s += cost.readback_s;
            total.encode_s += cost.encode_s;
            total.encode_wait_s += cost.encode_wait_s;
            frames.push_back({{"frame", k},
                              {"simulate_s", simulate_seconds[k]},
                              {"render_s", cost.render_s},
                              {"readback_s", cost.readback_s},
                              {"encode_s", cost.encode_s},
                              {"encode_wait_s", cost.encode_wait_s}});
        }
        // Stats, exports, handing frames to the writers: what the sinks took
        // beyond drawing, reading back and waiting for the encoder.
        const double output =
            std::max(0.0, sinks_s - total.render_s - total.readback_s - total.encode_wait_s);
        // The frames libx264 held back are encoded at the end, while the run waits.
        if (const auto times = render ? render->encode_times() : std::nullopt) {
            total.encode_s += times->flush_seconds;
            total.encode_wait_s += times->finish_wait_seconds;
        }
        StageTimes after, overlapped;
        after.add(Stage::frame_statistics, frame_fields_s);
        after.add(Stage::render, total.render_s);
        after.add(Stage::readback, total.readback_s);
        after.add(Stage::encode_wait, total.encode_wait_s);
        after.add(Stage::output, output);
        overlapped.add(Stage::encode, total.encode_s);
        stage_report =
            stage_rows(sim.stage_times(), after, wall(), sim.particle_steps(), overlapped);
        record.document["stages"] = stages_json(stage_report);
        record.document["timings"] = {{"total",
                                       {{"simulate_s", simulate_total},
                                        {"render_s", total.render_s},
                                        {"readback_s", total.readback_s},
                                        {"encode_s", total.encode_s},
                                        {"encode_wait_s", total.encode_wait_s}}},
                                      {"frames", frames}};
    };
    try {
        for (std::uint64_t k = 0; k < frames; ++k) {
            // A frame is taken when simulation time crosses k / fps.
            const double frame_time = double(k) / scene.fps;
            const auto simulate_start = std::chrono::steady_clock::now();
            while (!sim.reached(frame_time)) {
                if (interrupt_signal.load() != 0)
                    break;
                sim.step_toward(frame_time);
            }
            if (interrupt_signal.load() != 0) {
                progress.done();
                finish_sinks();
                record_timings();
                record.save("interrupted", written, sim.steps(), sim.time(), wall(),
                            fmt::format("stopped by signal {}", interrupt_signal.load()));
                fmt::print(stderr, "sphclip: interrupted at t = {:.4g} s; {} frames kept in {}\n",
                           sim.time(), written, folder.string());
                return exit_interrupted;
            }
            sim.update_fields();
            simulate_seconds.push_back(
                std::chrono::duration<double>(std::chrono::steady_clock::now() - simulate_start)
                    .count());
            snapshot.frame = k;
            snapshot.steps = sim.steps();
            snapshot.time = sim.time();
            snapshot.steps_taken = sim.take_counters();
            const auto fields_start = std::chrono::steady_clock::now();
            snapshot.stats = measure_frame(sim.params(), sim.state());
            snapshot.wall_seconds = wall();
            copy_fields(sim.state(), snapshot, fields);
            if (render && D == 3 && scene.render.cull_buried)
                mark_buried(sim.state(), sim.neighbours(), scene.fluid.spacing, snapshot.buried);
            const auto sinks_start = std::chrono::steady_clock::now();
            frame_fields_s += std::chrono::duration<double>(sinks_start - fields_start).count();
            for (auto& sink : sinks)
                sink->write(snapshot);
            sinks_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - sinks_start)
                           .count();
            ++written;
            progress.update(k, frames, sim.time(), sim.steps(), wall());
        }
        progress.done();
        // Inside the try: an encoder error may surface only here.
        finish_sinks();
    } catch (const UnstableError& e) {
        progress.done();
        try {
            finish_sinks();
        } catch (const std::exception& sink_error) {
            // A sink failed before the blow-up: a failed run, as on the
            // sequential path, where the failure came first.
            record_timings();
            record.save("failed", written, sim.steps(), sim.time(), wall(), sink_error.what());
            throw;
        }
        record_timings();
        record.save("unstable", written, sim.steps(), sim.time(), wall(), e.what());
        fmt::print(stderr, "sphclip: error: {}\nsphclip: the {} frames before it are kept in {}.\n",
                   e.what(), written, folder.string());
        return exit_unstable;
    } catch (const std::exception& e) {
        // Disk full, encoder failure: finalise what can be, record why, exit 1.
        progress.done();
        try {
            finish_sinks();
        } catch (const std::exception&) {
            // the first error is the one to report
        }
        record_timings();
        record.save("failed", written, sim.steps(), sim.time(), wall(), e.what());
        throw;
    }
    const double seconds = wall();
    record_timings();
    record.save("completed", written, sim.steps(), sim.time(), seconds);
    if (!options.quiet)
        fmt::print("sphclip: done: {} steps, {} frames in {:.2f} s ({:.3g} particle-steps/s)\n{}",
                   sim.steps(), written, seconds,
                   seconds > 0 ? double(sim.particle_steps()) / seconds : 0.0,
                   stages_table(stage_report));
    return exit_success;
}

} // namespace

int run_command(const RunOptions& options) {
    Scene scene = options.scene ? load_scene(*options.scene, options.overrides)
                                : default_scene(options.overrides);
    if (options.fast_preview)
        make_fast_preview(scene);
    const fs::path folder = options.out ? *options.out : output_folder(scene);
    // The GL context before any output: when none can be made, nothing is written.
    std::unique_ptr<GlContext> gl_context;
    if (options.png || options.mp4)
        gl_context =
            make_gl_context(options.backend.empty() ? scene.render.backend : options.backend);
    prepare_output_folder(folder);
    remove_earlier_frames(folder);
    if (options.threads > 0)
        omp_set_num_threads(options.threads);
    return scene.dimension == 2 ? run_clip<2>(scene, folder, options, std::move(gl_context))
                                : run_clip<3>(scene, folder, options, std::move(gl_context));
}

} // namespace sph
