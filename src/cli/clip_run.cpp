#include "cli/clip_run.hpp"

#include "cli/build_info.hpp"
#include "cli/console.hpp"
#include "cli/exit_codes.hpp"
#include "cli/progress.hpp"
#include "cli/stage_report.hpp"
#include "cli/stop_signals.hpp"
#include "output/files.hpp"
#include "output/particle_export.hpp"
#include "output/stats_csv.hpp"
#include "output/surface_export.hpp"
#include "parallel/rank_partition.hpp"
#include "parallel/render_exchange.hpp"
#include "parallel/thread_count_tuner.hpp"
#include "parallel/world.hpp"
#include "render/frame_renderer.hpp"
#include "render/render_sink.hpp"
#include "scene/scene_setup.hpp"
#include "sph/surface.hpp"
#include "sph/wall_clock.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <optional>
#include <string>
#include <unistd.h>
#include <utility>
#include <vector>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// How a run ended, as run.json's "status" says it.
enum class RunStatus { completed, interrupted, unstable, failed };

const char* status_name(RunStatus status) {
    switch (status) {
    case RunStatus::completed:
        return "completed";
    case RunStatus::interrupted:
        return "interrupted";
    case RunStatus::unstable:
        return "unstable";
    case RunStatus::failed:
        return "failed";
    }
    return "failed";
}

struct RunEnd {
    RunStatus status = RunStatus::completed;
    std::string error;            // run.json "error"; empty: none
    std::exception_ptr exception; // failed: rethrown once run.json says so
};

std::string message_of(const std::exception_ptr& error) {
    try {
        std::rethrow_exception(error);
    } catch (const std::exception& e) {
        return e.what();
    } catch (...) {
        return "unknown error";
    }
}

// run.json, written whole as the run starts and as it ends, and readable
// whenever the run ends, a full disk included (docs/contract.md, "A full
// disk"). The final form is written atomically, so a reader never sees a torn
// file. When that cannot be done for want of room (a new file's blocks, or
// `ulimit -f`), it is written in place over the starting form instead
// (write_file_in_place), which needs no free space: for that, the starting
// form reserves room, padded with spaces after the JSON (which parsers skip)
// to `final_room` bytes more than it needs. Written spaces, not fallocate():
// they are real blocks on every filesystem, NFS and tmpfs included.
struct RunRecord {
    json document;
    fs::path path;
    std::size_t reserved = 0; // bytes of the starting form, padding included

    // More than the final form adds (status, counts, error, the stage table
    // and the timing totals); per-frame timings that do not fit are dropped.
    static constexpr std::size_t final_room = 16 << 10;

    void start(std::size_t particles) {
        document["status"] = "running";
        document["frames"] = 0;
        document["steps"] = 0;
        document["simulated_time"] = 0;
        document["wall_s"] = 0;
        document["final_particles"] = particles;
        std::string text = document.dump(2) + "\n";
        text.append(final_room - 1, ' ');
        text += '\n';
        reserved = text.size();
        write_file_atomically(path, text);
    }

    // How the final form was written: "" atomically, else a note for the
    // user. Throws when it could not be written at all.
    std::string finish(const std::string& status, std::uint64_t frames, std::uint64_t steps,
                       double simulated, double wall, std::size_t particles,
                       const std::string& error) {
        document["status"] = status;
        document["frames"] = frames;
        document["steps"] = steps;
        document["simulated_time"] = simulated;
        document["wall_s"] = wall;
        document["final_particles"] = particles;
        document["ended_utc"] = utc_iso8601(std::chrono::system_clock::now());
        if (!error.empty())
            document["error"] = error;
        const std::string text = document.dump(2) + "\n";
        try {
            write_file_atomically(path, text);
            return {};
        } catch (const OutOfSpaceError&) {
        }
        // No room for a new file: over the reserved bytes, the per-frame
        // timings dropped if the whole does not fit.
        if (text.size() <= reserved) {
            write_file_in_place(path, text);
            return "rewritten in place, the disk being full";
        }
        document["timings"].erase("frames");
        document["run_json"] = "written in place on a full disk; the per-frame timings were "
                               "dropped for want of room";
        write_file_in_place(path, document.dump(2) + "\n");
        return "rewritten in place, the disk being full; its per-frame timings were dropped";
    }
};

// One x264 thread, by measurement (tests/bench/results/encode.csv, README
// "What encoding costs"): on 2 busy cores it encodes fastest, it leaves the
// other core to the simulation while it overlaps it, and the clip's bytes do
// not depend on the machine's core count, as libx264's choice would.
constexpr int encoder_threads = 1;

template <int D>
class ClipRun {
  public:
    // Setup: the simulation, the sinks, run.json saying "running", and the
    // run's first lines on the terminal.
    ClipRun(const Scene& scene, const fs::path& folder, const RunOptions& options,
            std::unique_ptr<GlContext> gl_context)
        : scene_(scene), folder_(folder), options_(options), derived_(derive(scene)),
          // Over MPI ranks, each step shared out (docs/mpi.md).
          sim_(make_simulation<D>(scene, derived_,
                                  [&](const Params<D>& params, const EffectList<D>& effects) {
                                      return parallel::make_rank_partition<D>(params, effects,
                                                                              scene.file);
                                  })),
          frames_(frame_count(scene.duration, scene.fps)),
          progress_(progress_mode(options.progress, options.quiet || !parallel::leader(),
                                  isatty(STDOUT_FILENO)),
                    options.progress_interval_s) {
        // Over MPI ranks rank 0 alone has sinks and writes run.json.
        // Every rank draws its own spheres when frames are composited by
        // depth (render/depth_composite.hpp); the exchange is made on every
        // rank at once.
        if (composite_from_)
            exchange_ = parallel::make_render_exchange(*composite_from_);
        if (leader_)
            add_sinks(std::move(gl_context));
        if (exchange_ && render_)
            render_->share_over_ranks(exchange_.get());
        if (exchange_ && !leader_) {
            rank_gl_ = options_.backend.empty()
                           ? make_gl_context(scene_.render.backend)
                           : make_gl_context(std::string_view(options_.backend));
            rank_renderer_ = std::make_unique<FrameRenderer>(make_render_settings(scene_));
            rank_renderer_->share_over_ranks(exchange_.get());
        }
        // Only the fields some sink reads are computed for output and copied
        // (rank 0's sinks: every rank computes its share as rank 0 asks).
        for (const auto& sink : sinks_)
            fields_ |= sink->fields();
        fields_.pressure = parallel::leader_says(fields_.pressure);
        // Marked by every rank together when rank 0 draws (3D culling).
        cull_buried_ =
            D == 3 && scene_.render.cull_buried && parallel::leader_says(render_ != nullptr);
        sim_.set_output_fields(fields_);
        // No --threads: the count is measured as the run goes. Over MPI ranks
        // each rank keeps all its cores (the ranks step in lockstep).
        if (options_.threads == 0 && parallel::size() == 1 && omp_get_max_threads() > 1)
            tuner_.emplace(omp_get_max_threads(), parallel::free_cores_of_this_machine());
        if (!leader_)
            return;
        record_.path = folder_ / "run.json";
        record_.document = starting_document();
        record_.start(sim_.particle_count());
        if (!options_.quiet)
            print_start();
    }

    // The frame loop, then finish(), whatever ended the loop.
    int run() {
        const StopSignals stop_signals;
        start_ = Clock::now();
        RunEnd end;
        try {
            end = simulate_frames();
        } catch (const UnstableError& e) {
            end = {RunStatus::unstable, e.what(), nullptr};
        } catch (const std::exception& e) {
            // Disk full, encoder failure: finish what can be, record why.
            end = {RunStatus::failed, e.what(), std::current_exception()};
        }
        return finish(std::move(end));
    }

  private:
    // Each frame goes to stats.csv, then the particle exports, then the
    // pictures. The GL sink is made first: it owns the context.
    void add_sinks(std::unique_ptr<GlContext> gl_context) {
        // With render.style = surface and --export surface, one surface a
        // frame for both: the export reconstructs it, the picture reuses it.
        // (Made whatever the style: it reconstructs nothing until asked.)
        const RenderSettings render_settings = make_render_settings(scene_);
        const auto surface = std::make_shared<FrameSurface>(
            render_settings.field, render_settings.spacing, render_settings.surface);
        std::unique_ptr<RenderSink> render;
        if (gl_context)
            render = std::make_unique<RenderSink>(
                std::move(gl_context), render_settings,
                options_.png ? folder_ / "frames" : fs::path(),
                options_.mp4 ? folder_ / "clip.mp4" : fs::path(), scene_.fps,
                Mp4Options{scene_.render.video_quality,
                           std::string(video_preset_name(scene_.render.video_preset)),
                           encoder_threads},
                EncodeThread::worker, surface);
        sinks_.push_back(std::make_unique<StatsCsv>(folder_ / "stats.csv"));
        for (const auto& format : options_.exports) {
            if (format == "surface") {
                sinks_.push_back(
                    std::make_unique<SurfaceExport>(folder_, render_settings, surface));
                continue;
            }
            fs::create_directories(folder_ / "particles");
            if (format == "csv")
                sinks_.push_back(std::make_unique<ParticleCsv>(folder_));
            else if (format == "vtk" || format == "vtk-ascii")
                sinks_.push_back(std::make_unique<ParticleVtk>(
                    folder_, format == "vtk" ? ParticleVtk::Encoding::binary
                                             : ParticleVtk::Encoding::ascii));
        }
        if (render) {
            render_ = render.get();
            sinks_.push_back(std::move(render));
        }
    }

    json starting_document() const {
        json document = {
            {"sphclip_version", SPHCLIP_VERSION},
            {"command", options_.command_line},
            {"scene_file", scene_.file},
            {"scene_file_absolute", options_.scene_file_absolute.empty()
                                        ? json(nullptr)
                                        : json(options_.scene_file_absolute)},
            {"scene", to_json(scene_)},
            {"derived",
             {{"smoothing_length", derived_.h},
              {"mass", derived_.mass},
              {"dt", derived_.dt},
              {"sound_speed", derived_.sound_speed},
              {"max_speed", sim_.params().watchdog.max_speed}}},
            {"particles", sim_.particle_count()},
            {"threads", omp_get_max_threads()},
            {"mpi", {{"ranks", parallel::size()}}},
            {"started_utc", utc_iso8601(started_)},
            {"build", build_json()},
            {"machine", machine_json()},
            {"solver", std::string(sim_.solver().name())},
            {"neighbour_search", std::string(sim_.search().name())},
            {"fast_preview", options_.fast_preview},
            {"outputs",
             {{"stats", "stats.csv"},
              {"exports", options_.exports},
              {"png", options_.png ? json("frames/") : json(false)},
              {"mp4", options_.mp4 ? json("clip.mp4") : json(false)}}},
            {"output_fields", {{"pressure", fields_.pressure}}},
        };
        if (options_.rerun_of)
            document["rerun_of"] = {{"run_json", options_.rerun_of->run_json.string()},
                                    {"sphclip_version", options_.rerun_of->sphclip_version},
                                    {"git_commit", options_.rerun_of->git_commit},
                                    {"started_utc", options_.rerun_of->started_utc}};
        if (render_)
            document["gl"] = {{"backend", render_->gl_info().backend},
                              {"vendor", render_->gl_info().vendor},
                              {"renderer", render_->gl_info().renderer},
                              {"version", render_->gl_info().version}};
        return document;
    }

    void print_start() const {
        say("sphclip: {} ({}D, {} solver): {} particles, h = {:.4g} m, m = {:.4g} kg, "
            "dt = {:.4g} s, {} frames of {:.4g} s -> {}\n",
            scene_.name, D, solver_capabilities(scene_.solver.name).name, sim_.particle_count(),
            derived_.h, derived_.mass, derived_.dt, frames_, scene_.duration, folder_.string());
        if (options_.fast_preview)
            say("sphclip: fast preview: half-size frames ({}x{}), x264 preset {}\n",
                scene_.render.size[0], scene_.render.size[1],
                video_preset_name(scene_.render.video_preset));
        if (render_)
            say("sphclip: rendering {}x{} with {} ({}, OpenGL {})\n", scene_.render.size[0],
                scene_.render.size[1], render_->gl_info().backend, render_->gl_info().renderer,
                render_->gl_info().version);
    }

    // Frames at k / fps, and one more at the duration when it falls between
    // two: a run always ends at the simulated time it was asked for (0.05 s
    // at 10 fps is frames at 0 and 0.05 s, not frame 0 alone).
    static std::uint64_t frame_count(double duration, double fps) {
        const double intervals = duration * fps;
        const double whole = std::floor(intervals + 1e-9);
        return static_cast<std::uint64_t>(whole) + 1 + (intervals - whole > 1e-9 ? 1 : 0);
    }
    double frame_time(std::uint64_t k) const {
        return std::min(double(k) / scene_.fps, scene_.duration);
    }

    RunEnd simulate_frames() {
        for (std::uint64_t k = 0; k < frames_; ++k) {
            // A frame is taken when simulation time crosses its time.
            if (!simulate_until(frame_time(k)))
                return {RunStatus::interrupted,
                        StopSignals::received() != 0
                            ? fmt::format("stopped by signal {}", StopSignals::received())
                            : std::string("stopped by a signal to another MPI rank"),
                        nullptr};
            take_snapshot(k);
            // No stats row or export ever holds inf or NaN: such a frame
            // ends the run as unstable before any of it is written. (Over
            // MPI ranks rank 0 sees every particle and names the first; the
            // others look at their own and decide with it.)
            if (std::string bad = non_finite_in_snapshot(); parallel::any_rank(!bad.empty()))
                return {RunStatus::unstable,
                        fmt::format("frame {} (t = {:.4g} s, step {}) holds a non-finite value: "
                                    "{}; none of the frame was written",
                                    k, sim_.time(), sim_.steps(), bad),
                        nullptr};
            write_snapshot();
            progress_.update(k, frames_, sim_.time(), sim_.steps(), wall());
        }
        return {};
    }

    // Steps to `time` and brings the frame fields up to date; false when a
    // signal asked to stop first (checked between steps).
    bool simulate_until(double time) {
        const auto start = Clock::now();
        // Over MPI ranks the ranks decide together, between the same steps.
        bool stop = false;
        while (!sim_.reached(time) && !(stop = parallel::any_rank(StopSignals::received() != 0)))
            step_toward(time);
        if (!stop)
            stop = parallel::any_rank(StopSignals::received() != 0);
        if (stop)
            return false;
        sim_.update_fields();
        simulate_seconds_.push_back(seconds_since(start));
        return true;
    }

    // One step, with the thread count the tuner chooses when the user gave
    // none (parallel/thread_count_tuner.hpp).
    void step_toward(double time) {
        if (!tuner_) {
            sim_.step_toward(time);
            return;
        }
        tuner_->step([&] {
            const std::uint64_t before = sim_.particle_steps();
            sim_.step_toward(time);
            return sim_.particle_steps() - before;
        });
    }

    // Counters, statistics and the particle fields some sink reads.
    void take_snapshot(std::uint64_t k) {
        snapshot_.frame = k;
        snapshot_.steps = sim_.steps();
        snapshot_.time = sim_.time();
        snapshot_.steps_taken = sim_.take_counters();
        const auto start = Clock::now();
        // Over MPI ranks rank 0's state() is every particle, the others'
        // their own: only rank 0 writes the frame (the others draw their
        // own spheres when frames are composited by depth).
        if (leader_)
            snapshot_.stats = measure_frame(sim_.params(), sim_.state());
        snapshot_.wall_seconds = wall();
        copy_fields(sim_.state(), snapshot_, fields_);
        snapshot_.owned = sim_.share_size();
        snapshot_.total = sim_.particle_count();
        if (cull_buried_)
            sim_.mark_buried(scene_.fluid.spacing, snapshot_.buried);
        frame_fields_s_ += seconds_since(start);
    }

    // The first non-finite value of the frame's statistics and particle
    // fields, named; "" when all are finite.
    std::string non_finite_in_snapshot() const {
        const FrameStats& stats = snapshot_.stats;
        const std::pair<const char*, double> totals[] = {
            {"density_avg", stats.density_avg},
            {"density_max", stats.density_max},
            {"density_error_avg_pct", stats.density_error_avg_pct},
            {"density_error_max_pct", stats.density_error_max_pct},
            {"kinetic_energy", stats.kinetic_energy},
            {"max_speed", stats.max_speed},
        };
        for (const auto& [name, value] : totals)
            if (!std::isfinite(value))
                return fmt::format("{} = {}", name, value);
        const std::pair<const char*, const std::vector<Real>*> fields[] = {
            {"position", &snapshot_.position},
            {"velocity", &snapshot_.velocity},
            {"density", &snapshot_.density},
            {"pressure", &snapshot_.pressure},
        };
        for (const auto& [name, values] : fields) {
            const std::size_t per_particle =
                values->size() / std::max<std::size_t>(snapshot_.id.size(), 1);
            for (std::size_t i = 0; i < values->size(); ++i)
                if (!std::isfinite((*values)[i]))
                    return fmt::format("particle {} has {} = {}",
                                       snapshot_.id.empty() || per_particle == 0
                                           ? i
                                           : std::size_t(snapshot_.id[i / per_particle]),
                                       name, (*values)[i]);
        }
        return {};
    }

    void write_snapshot() {
        const auto start = Clock::now();
        for (auto& sink : sinks_)
            sink->write(snapshot_);
        // Over MPI ranks, by depth: this rank's spheres to rank 0.
        if (rank_renderer_)
            rank_renderer_->render(snapshot_);
        sinks_s_ += seconds_since(start);
        ++written_;
        say_new_warnings();
    }

    // The renderer's warnings (a colour range most particles fall outside)
    // on stderr as they arise; run.json "warnings" lists them at the end.
    void say_new_warnings() {
        if (!render_)
            return;
        for (; warned_ < render_->warnings().size(); ++warned_)
            say(stderr, "sphclip: warning: {}\n", render_->warnings()[warned_]);
    }

    // Every ending comes here: the sinks are finished (the video finalised),
    // run.json records how the run ended and where the time went, and the
    // ending is told.
    int finish(RunEnd end) {
        progress_.done(wall());
        // An encoder error may surface only as the video is finalised: the
        // run failed, unless it had failed already (the first error is the
        // one to report) or a sink failed before a blow-up (then the failure
        // came first, as on the sequential path).
        std::vector<std::exception_ptr> sink_errors = finish_sinks();
        if (!sink_errors.empty() && end.status != RunStatus::failed) {
            end = {RunStatus::failed, message_of(sink_errors.front()), sink_errors.front()};
            sink_errors.erase(sink_errors.begin());
        }
        const bool out_of_space = is_out_of_space_error(end.exception);
        if (out_of_space)
            end.error = "out of disk space: " + end.error;
        const double seconds = wall();
        const std::vector<StageRow> stages = record_timings(seconds);
        if (render_ && !render_->warnings().empty())
            record_.document["warnings"] = render_->warnings();
        if (!leader_) {
            // Rank 0 records and tells; a failure here ends the job (main()).
            if (end.status == RunStatus::failed)
                std::rethrow_exception(end.exception);
            return end.status == RunStatus::completed  ? exit_success
                   : end.status == RunStatus::unstable ? exit_unstable
                                                       : exit_interrupted;
        }
        if (const Partition<D>* partition = sim_.partition()) {
            record_.document["mpi"] = partition->report();
            record_.document["mpi"]["render"] = render_over_ranks_json();
        }
        if (render_ && !render_->poses().empty())
            record_.document["camera"] = record_cameras(*render_);
        std::string run_json_note;
        try {
            run_json_note = record_.finish(status_name(end.status), written_, sim_.steps(),
                                           sim_.time(), seconds, sim_.particle_count(), end.error);
        } catch (const std::exception& e) {
            if (!out_of_space)
                throw;
            run_json_note = fmt::format("lost, it says \"running\": {}", e.what());
        }
        if (out_of_space) {
            report_out_of_space(end.error, sink_errors, run_json_note);
            return exit_failure;
        }
        switch (end.status) {
        case RunStatus::completed:
            if (!options_.quiet)
                say("sphclip: done: {} steps, {} frames in {:.2f} s ({:.3g} particle-steps/s)\n{}",
                    sim_.steps(), written_, seconds,
                    seconds > 0 ? double(sim_.particle_steps()) / seconds : 0.0,
                    stages_table(stages));
            return exit_success;
        case RunStatus::interrupted:
            say(stderr, "sphclip: interrupted at t = {:.4g} s; {} frames kept in {}\n", sim_.time(),
                written_, folder_.string());
            return exit_interrupted;
        case RunStatus::unstable:
            say(stderr, "sphclip: error: {}\nsphclip: the {} frames before it are kept in {}.\n",
                end.error, written_, folder_.string());
            return exit_unstable;
        case RunStatus::failed:
            break;
        }
        // main() says why and picks the exit code.
        std::rethrow_exception(end.exception);
    }

    // Whole files in `folder`, temporaries left out.
    static std::size_t count_files(const fs::path& folder) {
        std::error_code ec;
        std::size_t count = 0;
        for (const auto& entry : fs::directory_iterator(folder, ec))
            count += entry.path().extension() != ".partial";
        return count;
    }

    static long count_lines(const fs::path& path) {
        std::FILE* file = std::fopen(path.c_str(), "rb");
        if (!file)
            return 0;
        long lines = 0;
        for (int c; (c = std::getc(file)) != EOF;)
            lines += c == '\n';
        std::fclose(file);
        return lines;
    }

    static bool is_out_of_space_error(const std::exception_ptr& error) {
        if (!error)
            return false;
        try {
            std::rethrow_exception(error);
        } catch (const OutOfSpaceError&) {
            return true;
        } catch (...) {
            return false;
        }
    }

    // A full disk: what stopped the run, what each output kept, what was lost
    // (`sink_errors`: the errors as the outputs were finished, after the one
    // that ended the run).
    void report_out_of_space(const std::string& error,
                             const std::vector<std::exception_ptr>& sink_errors,
                             const std::string& run_json_note) const {
        std::vector<std::string> kept, lost;
        // Counted, not inferred: the PNGs and the video are written on
        // worker threads, which lag the frame loop.
        kept.push_back(fmt::format("stats.csv ({} rows)", count_lines(folder_ / "stats.csv") - 1));
        if (fs::exists(folder_ / "particles"))
            kept.push_back(
                fmt::format("particles/ ({} files)", count_files(folder_ / "particles")));
        if (fs::exists(folder_ / "surface"))
            kept.push_back(fmt::format("surface/ ({} files)", count_files(folder_ / "surface")));
        if (render_ && options_.png)
            kept.push_back(fmt::format("frames/ ({} PNGs)", count_files(folder_ / "frames")));
        if (render_ && options_.mp4) {
            if (fs::exists(folder_ / "clip.mp4"))
                kept.push_back("clip.mp4 (the frames so far, playable)");
            else if (written_ == 0)
                lost.push_back("clip.mp4: no frame was written");
            else
                lost.push_back(
                    "clip.mp4: its frames and index could not all be written, and an MP4 "
                    "without its index does not play, so it was removed");
        }
        if (run_json_note.empty())
            kept.push_back("run.json (status \"failed\", with the reason)");
        else if (run_json_note.starts_with("lost"))
            lost.push_back("run.json: " + run_json_note);
        else
            kept.push_back(
                fmt::format("run.json (status \"failed\", with the reason; {})", run_json_note));
        if (written_ < frames_)
            lost.push_back(
                fmt::format("frames {} to {}: the run stopped at t = {:.4g} s of {:.4g} s",
                            written_, frames_ - 1, sim_.time(), scene_.duration));
        for (const auto& sink_error : sink_errors)
            if (const std::string message = message_of(sink_error);
                error.find(message) == std::string::npos) // the same error, seen again
                lost.push_back(message);
        say(stderr, "sphclip: error: {}\nsphclip: the run stopped; kept in {}: {}\n", error,
            folder_.string(), fmt::join(kept, ", "));
        for (const auto& line : lost)
            say(stderr, "sphclip: lost: {}\n", line);
    }

    // Every sink is finished, even after one fails (so the video is
    // finalised whatever happens); returns their errors, the first first.
    std::vector<std::exception_ptr> finish_sinks() {
        std::vector<std::exception_ptr> errors;
        for (auto& sink : sinks_) {
            try {
                sink->finish();
            } catch (...) {
                errors.push_back(std::current_exception());
            }
        }
        return errors;
    }

    // run.json "camera": the first and last frames' cameras as render.camera
    // blocks to paste into a scene (each reproduces its frame), and every
    // frame's in camera.csv beside it.
    json record_cameras(const RenderSink& render) const {
        const auto& poses = render.poses();
        const int dim = render.dimension();
        json out = {{"fit", render.camera_fit()},
                    {"first_frame", poses.front().frame},
                    {"first", camera_block(poses.front().pose, dim, render.scene_aspect())},
                    {"last_frame", poses.back().frame},
                    {"last", camera_block(poses.back().pose, dim, render.scene_aspect())}};
        std::string csv = dim == 2 ? "frame,time_s,centre_x_m,centre_y_m,height_m\n"
                                   : "frame,time_s,position_x_m,position_y_m,position_z_m,"
                                     "target_x_m,target_y_m,target_z_m,up_x,up_y,up_z,fov_deg\n";
        for (const auto& p : poses) {
            const CameraPose& c = p.pose;
            csv += dim == 2 ? fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g}\n", p.frame, p.time,
                                          c.target.x, c.target.y, c.height)
                            : fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},"
                                          "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                                          p.frame, p.time, c.position.x, c.position.y, c.position.z,
                                          c.target.x, c.target.y, c.target.z, c.up.x, c.up.y,
                                          c.up.z, c.fov);
        }
        try {
            write_file_atomically(folder_ / "camera.csv", csv);
            out["frames"] = "camera.csv";
        } catch (const std::exception& e) {
            out["frames"] = fmt::format("camera.csv not written: {}", e.what());
        }
        return out;
    }

    // 3D with the scene rectangle's aspect: the layout too is the frame's.
    static json camera_block(const CameraPose& pose, int dimension, double aspect) {
        auto vector = [](const glm::dvec3& v, int n) {
            return std::vector<double>(&v[0], &v[0] + n);
        };
        if (dimension == 2)
            return {{"centre", vector(pose.target, 2)}, {"height", pose.height}};
        return {{"position", vector(pose.position, 3)},
                {"target", vector(pose.target, 3)},
                {"up", vector(pose.up, 3)},
                {"fov", pose.fov},
                {"aspect", aspect}};
    }

    // run.json "timings" (per frame and in all) and "stages"; returns the
    // stage rows for the terminal. The MP4 encoder runs on a worker thread:
    // its busy time (`encode`) overlaps the main thread's stages, and only
    // the main thread's wait for it (`encode wait`) adds to the wall time.
    std::vector<StageRow> record_timings(double wall_seconds) {
        const std::vector<FrameCost> costs = render_ ? render_->costs() : std::vector<FrameCost>{};
        json frames = json::array();
        double simulate_total = 0;
        FrameCost total;
        for (std::size_t k = 0; k < simulate_seconds_.size(); ++k) {
            const FrameCost cost = k < costs.size() ? costs[k] : FrameCost{};
            simulate_total += simulate_seconds_[k];
            total.render_s += cost.render_s;
            total.composite_s += cost.composite_s;
            total.readback_s += cost.readback_s;
            total.encode_s += cost.encode_s;
            total.encode_wait_s += cost.encode_wait_s;
            frames.push_back({{"frame", k},
                              {"simulate_s", simulate_seconds_[k]},
                              {"render_s", cost.render_s},
                              {"readback_s", cost.readback_s},
                              {"encode_s", cost.encode_s},
                              {"encode_wait_s", cost.encode_wait_s}});
        }
        // Stats, exports, handing frames to the writers: what the sinks took
        // beyond drawing, reading back and waiting for the encoder.
        const double output =
            std::max(0.0, sinks_s_ - total.render_s - total.readback_s - total.encode_wait_s);
        // The frames libx264 held back are encoded at the end, while the run waits.
        if (const auto times = render_ ? render_->encode_times() : std::nullopt) {
            total.encode_s += times->flush_seconds;
            total.encode_wait_s += times->finish_wait_seconds;
        }
        StageTimes after, overlapped;
        after.add(Stage::frame_statistics, frame_fields_s_);
        after.add(Stage::render, total.render_s - total.composite_s);
        after.add(Stage::composite, total.composite_s);
        after.add(Stage::readback, total.readback_s);
        after.add(Stage::encode_wait, total.encode_wait_s);
        after.add(Stage::output, output);
        overlapped.add(Stage::encode, total.encode_s);
        std::vector<StageRow> stages =
            stage_rows(sim_.stage_times(), after, wall_seconds, sim_.particle_steps(), overlapped,
                       sim_.solve_work(), sim_.steps());
        record_.document["stages"] = stages_json(stages);
        json limits = json::object();
        for (std::size_t k = 0; k < time_step_limit_names.size(); ++k)
            limits[std::string(time_step_limit_names[k])] = sim_.time_step_limits()[k];
        record_.document["time_step_limits"] = limits;
        record_.document["thread_counts"] = thread_counts_json();
        record_.document["wait_policy"] = wait_policy_json();
        if (tuner_)
            record_.document["thread_tuning"] = {{"free_cores_known", tuner_->free_cores_known()},
                                                 {"first_threads", tuner_->first_threads()},
                                                 {"changes", tuner_->changes()},
                                                 {"tries_skipped", tuner_->tries_skipped()}};
        record_.document["timings"] = {{"total",
                                        {{"simulate_s", simulate_total},
                                         {"render_s", total.render_s},
                                         {"readback_s", total.readback_s},
                                         {"encode_s", total.encode_s},
                                         {"encode_wait_s", total.encode_wait_s}}},
                                       {"frames", frames}};
        return stages;
    }

    double wall() const { return seconds_since(start_); }

    // run.json "mpi" "render": how the frames reached rank 0's picture.
    json render_over_ranks_json() const {
        const auto& choice = scene_.render.mpi_composite;
        const std::size_t by_depth = render_ ? render_->frames_composited() : 0;
        return {{"mpi_composite", choice ? json(choice_name(*choice)) : json("auto")},
                {"depth_from_particles", composite_from_ ? json(*composite_from_) : json(nullptr)},
                {"frames_by_depth", by_depth},
                {"frames_gathered", render_ ? written_ - by_depth : 0}};
    }

    // run.json "thread_counts": the steps at each thread count.
    json thread_counts_json() const {
        json counts = json::array();
        if (!tuner_) {
            counts.push_back({{"threads", omp_get_max_threads()},
                              {"steps", sim_.steps()},
                              {"chosen_by", options_.threads > 0 ? "--threads" : "all cores"}});
            return counts;
        }
        for (const auto& use : tuner_->uses())
            counts.push_back({{"threads", use.threads},
                              {"steps", use.steps},
                              {"seconds", use.seconds},
                              {"chosen_by", "measurement"}});
        return counts;
    }

    // run.json "wait_policy": how idle OpenMP threads waited, the
    // environment libgomp read (sphclip's GOMP_SPINCOUNT unless the user set
    // a policy; cli/wait_policy.hpp).
    static json wait_policy_json() {
        const auto variable = [](const char* name) {
            const char* value = std::getenv(name);
            return value ? json(value) : json(nullptr);
        };
        return {{"GOMP_SPINCOUNT", variable("GOMP_SPINCOUNT")},
                {"OMP_WAIT_POLICY", variable("OMP_WAIT_POLICY")}};
    }

    const bool leader_ = parallel::leader(); // rank 0, or the only process
    bool cull_buried_ = false;               // frames mark the buried particles
    const Scene& scene_;
    const fs::path folder_;
    const RunOptions& options_;
    const Derived derived_;
    Simulation<D> sim_;
    std::optional<parallel::ThreadCountTuner> tuner_; // none: a fixed thread count
    const std::uint64_t frames_;
    std::vector<std::unique_ptr<FrameSink>> sinks_;
    RenderSink* render_ = nullptr; // in sinks_, when frames are drawn
    // Over MPI ranks with depth compositing: the exchange (every rank), and
    // the other ranks' context and renderer, which draw their own spheres.
    const std::optional<std::size_t> composite_from_ =
        depth_composite_from(scene_, options_, parallel::size());
    std::unique_ptr<RankCompositing> exchange_;
    std::unique_ptr<GlContext> rank_gl_;
    std::unique_ptr<FrameRenderer> rank_renderer_;
    FrameFields fields_{.pressure = false};
    RunRecord record_;
    Progress progress_;
    Clock::time_point start_;
    // Wall-clock time as the run was set up: run.json "started_utc".
    const std::chrono::system_clock::time_point started_ = std::chrono::system_clock::now();
    Snapshot snapshot_;
    std::uint64_t written_ = 0;
    std::size_t warned_ = 0; // the renderer's warnings said so far
    // Where the time went beyond the simulation's own stages.
    std::vector<double> simulate_seconds_; // per frame: stepping and frame fields
    double frame_fields_s_ = 0;            // statistics and copies for the sinks
    double sinks_s_ = 0;                   // the sinks' write calls
};

} // namespace

// The flat layers lay a frame's samples side by side (depth_composite.hpp):
// 4 samples (RenderSettings::samples) times the width within llvmpipe's
// 16384-texel textures.
constexpr int layer_width_limit = 16384;

std::string depth_composite_problem(const Scene& scene) {
    if (scene.render.style != FluidStyle::spheres ||
        scene.render.spheres != SphereDrawing::impostor)
        return "depth compositing draws impostor spheres only (render.style spheres, "
               "render.spheres impostor); a surface is one of all the particles, and meshes' "
               "depth is per sample; use gather or auto";
    const RenderSettings settings = make_render_settings(scene);
    if (std::int64_t(settings.width) * settings.samples > layer_width_limit)
        return fmt::format("depth compositing lays a frame's {} samples a pixel side by side, "
                           "at most {} pixels wide: render.size's width {} is wider; use gather "
                           "or auto",
                           settings.samples, layer_width_limit / settings.samples, settings.width);
    return {};
}

std::optional<std::size_t> depth_composite_from(const Scene& scene, const RunOptions& options,
                                                int ranks) {
    if (ranks < 2 || !(options.png || options.mp4))
        return std::nullopt;
    const auto& choice = scene.render.mpi_composite;
    if (choice == MpiComposite::gather || !depth_composite_problem(scene).empty())
        return std::nullopt;
    return choice == MpiComposite::depth ? std::optional<std::size_t>(0)
                                         : auto_depth_from_particles;
}

int run_clip(const Scene& scene, const fs::path& folder, const RunOptions& options,
             std::unique_ptr<GlContext> gl_context) {
    if (scene.dimension == 2)
        return ClipRun<2>(scene, folder, options, std::move(gl_context)).run();
    return ClipRun<3>(scene, folder, options, std::move(gl_context)).run();
}

} // namespace sph
