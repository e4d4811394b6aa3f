#include "cli/run_command.hpp"

#include "cli/build_info.hpp"
#include "cli/clip_run.hpp"
#include "cli/console.hpp"
#include "cli/exit_codes.hpp"
#include "cli/output_folder.hpp"
#include "cli/progress.hpp"
#include "cli/set_options.hpp"
#include "cli/stop_signals.hpp"
#include "output/files.hpp"
#include "output/mp4_writer.hpp"
#include "parallel/world.hpp"
#include "render/fonts.hpp"
#include "render/gl_context.hpp"
#include "render/render_settings.hpp"
#include "render/surface/reconstruct.hpp"
#include "scene/input_error.hpp"
#include "sph/single_precision/single_passes.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fmt/format.h>
#include <memory>
#include <nlohmann/json.hpp>
#include <omp.h>
#include <unistd.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

// Half the size, rounded to even (yuv420p needs even sizes, so the video is
// not padded), and libx264's fastest preset. run.json's scene records both.
void make_fast_preview(Scene& scene) {
    for (int& side : scene.render.size)
        side = 2 * std::max(1, (side + 2) / 4);
    scene.render.video_preset = VideoPreset::ultrafast;
}

// A run.json that sphclip wrote: an object with sphclip_version and a scene
// object. Anything else (a scene file, a file that cannot be read or parsed)
// is none, and goes to load_scene, which names its problem.
std::optional<nlohmann::json> read_run_json(const fs::path& file) {
    std::string text;
    try {
        text = read_input_file(file, run_record_limit);
    } catch (const FileReadError&) {
        return std::nullopt;
    }
    auto document = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false,
                                          /*ignore_comments=*/true);
    if (document.is_object() && document.contains("sphclip_version") &&
        document.contains("scene") && document["scene"].is_object())
        return document;
    return std::nullopt;
}

std::string text_or_unknown(const nlohmann::json& document, const char* key) {
    const auto it = document.find(key);
    return it != document.end() && it->is_string() ? it->get<std::string>() : "unknown";
}

// The scene a run.json recorded (resolved: every key, derived values filled
// in), with the command line's overrides on top, and the run options it
// recorded where the command line gives none: --threads, --export, the GL
// backend; --no-png and --no-mp4 can only turn an output off. The scene is labelled with the
// run.json's path in messages, except that a scene with mesh obstacles is
// read as the recorded scene file, whose folder its OBJ files are relative to.
Scene rerun_scene(const fs::path& file, const nlohmann::json& document, RunOptions& options) {
    const std::string label = file.string();
    const nlohmann::json& recorded = document["scene"];
    std::string mesh_label = label;
    if (const auto effects = recorded.find("effects");
        effects != recorded.end() && effects->is_object() && effects->contains("obstacles")) {
        for (const auto& obstacle : (*effects)["obstacles"])
            if (obstacle.is_object() && obstacle.contains("mesh"))
                mesh_label = text_or_unknown(document, "scene_file_absolute");
    }
    if (mesh_label == "unknown")
        throw InputError(label, "scene_file_absolute",
                         "a scene with mesh obstacles is re-run from the recorded scene file's "
                         "folder, and this run.json does not record it");
    Scene scene = parse_scene(recorded.dump(), mesh_label, options.overrides);
    // The recorded output.name is the original scene's name (or its own).
    if (scene.output.name)
        scene.name = *scene.output.name;
    scene.file = label;
    options.scene_file_absolute = text_or_unknown(document, "scene_file_absolute");
    if (options.scene_file_absolute == "unknown")
        options.scene_file_absolute.clear();

    // The recorded thread count when the user fixed it (--threads); a count
    // that was measured as the run went is measured again (the bits are the
    // same for any count).
    const auto counts = document.find("thread_counts");
    const bool measured = counts != document.end() && counts->is_array() && !counts->empty() &&
                          counts->front().value("chosen_by", "") == "measurement";
    if (options.threads == 0 && !measured)
        if (const auto threads = document.find("threads");
            threads != document.end() && threads->is_number_integer() && *threads > 0)
            options.threads = threads->get<int>();
    if (const auto outputs = document.find("outputs");
        outputs != document.end() && outputs->is_object()) {
        if (options.exports.empty() && outputs->contains("exports") &&
            (*outputs)["exports"].is_array())
            for (const auto& format : (*outputs)["exports"])
                if (format.is_string())
                    options.exports.push_back(format.get<std::string>());
        if (outputs->contains("png") && (*outputs)["png"] == false)
            options.png = false;
        if (outputs->contains("mp4") && (*outputs)["mp4"] == false)
            options.mp4 = false;
    }
    // The GL context it drew with (frames from EGL and OSMesa may differ in
    // a few pixels), unless --backend names one.
    if (options.backend.empty())
        if (const auto gl = document.find("gl"); gl != document.end() && gl->is_object()) {
            const std::string backend = text_or_unknown(*gl, "backend");
            if (backend == "egl" || backend == "osmesa")
                options.backend = backend;
        }
    const std::string commit = document.contains("build") && document["build"].is_object()
                                   ? text_or_unknown(document["build"], "git_commit")
                                   : std::string("unknown");
    options.rerun_of = RerunSource{fs::absolute(file).lexically_normal(),
                                   text_or_unknown(document, "sphclip_version"), commit,
                                   text_or_unknown(document, "started_utc")};
    return scene;
}

// A re-run's folder: --out, or the recorded run's default folder with
// "-rerun" added (out/dam_break_2d-rerun/). Never the run.json's own
// folder: that would replace the run being reproduced.
fs::path rerun_folder(const RunOptions& options, const Scene& scene) {
    fs::path folder = options.out ? *options.out : output_folder(scene);
    if (!options.out)
        folder = folder.parent_path() / (folder.filename().string() + "-rerun");
    std::error_code ec;
    const fs::path source = fs::weakly_canonical(fs::absolute(*options.scene).parent_path(), ec);
    const fs::path target = fs::weakly_canonical(fs::absolute(folder), ec);
    if (source == target)
        throw InputError("command line", "--out",
                         fmt::format("{} is the folder of the run.json being re-run; a re-run "
                                     "would replace the run it reproduces: give another --out",
                                     folder.string()));
    return folder;
}

} // namespace

CLI::App* add_run_command(CLI::App& app, RunCommandLine& line) {
    RunOptions& run = line.options;
    auto* cmd = app.add_subcommand("run", "Simulate a scene and write its frames.");
    cmd->add_option("scene", line.scene, "Scene file (JSON); none: the built-in 2D dam break");
    cmd->add_option("--out", line.out, "Output folder (default out/<scene name>/)");
    cmd->add_option("--set", line.sets, "Override a scene field: --set solver.dt=2e-4 (repeatable)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    cmd->add_option("--threads", run.threads,
                    "Threads (default: up to all cores, the count measured as the run goes)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--duration", line.duration, "Simulated seconds (same as --set duration=S)")
        ->check(positive_finite_number());
    cmd->add_option("--fps", line.fps, "Frames per second (same as --set fps=N)")
        ->check(positive_finite_number());
    cmd->add_option("--export", run.exports,
                    "Data per frame: particles as csv, vtk (binary, compressed) or vtk-ascii; "
                    "surface: the fluid's surface mesh (.ply) and 3D level set (.vdb)")
        ->check(CLI::IsMember({"csv", "vtk", "vtk-ascii", "surface"}))
        ->allow_extra_args(false);
    cmd->add_flag("--no-png", line.no_png, "Write no PNG frames");
    cmd->add_flag("--no-mp4", line.no_mp4, "Write no MP4 video");
    cmd->add_flag("--quiet", run.quiet,
                  "No summary, and no progress unless --progress bar or lines is given");
    cmd->add_option("--progress", run.progress,
                    "auto (a bar on a terminal, else a line every 10 s), bar, lines or none")
        ->check(CLI::IsMember({"auto", "bar", "lines", "none"}));
    cmd->add_flag("--fast-preview", run.fast_preview,
                  "Half-size frames and the fastest x264 preset (ultrafast)");
    cmd->add_option("--backend", run.backend,
                    "Headless GL context: auto (EGL, then OSMesa), egl or osmesa "
                    "(default: the scene's render.backend)")
        ->check(CLI::IsMember({"auto", "egl", "osmesa"}));
    return cmd;
}

RunOptions run_options(const RunCommandLine& line, const std::string& command_line) {
    RunOptions run = line.options;
    if (!line.scene.empty())
        run.scene = line.scene;
    if (!line.out.empty())
        run.out = line.out;
    // --duration and --fps after the --set values: they win.
    run.overrides = parse_sets(line.sets);
    if (line.duration > 0)
        run.overrides.push_back({"duration", fmt::format("{}", line.duration)});
    if (line.fps > 0)
        run.overrides.push_back({"fps", fmt::format("{}", line.fps)});
    run.png = !line.no_png;
    run.mp4 = !line.no_mp4;
    run.command_line = command_line;
    run.progress_interval_s = progress_interval();
    return run;
}

int run_command(const RunOptions& given) {
    RunOptions options = given;
    const std::optional<nlohmann::json> recorded =
        options.scene ? read_run_json(*options.scene) : std::nullopt;
    Scene scene = recorded        ? rerun_scene(*options.scene, *recorded, options)
                  : options.scene ? load_scene(*options.scene, options.overrides)
                                  : default_scene(options.overrides);
    if (options.scene && !recorded)
        options.scene_file_absolute = fs::absolute(*options.scene).lexically_normal().string();
    if (options.fast_preview)
        make_fast_preview(scene);
    // A variant pinned by the environment that cannot run here stops the run
    // now, not at its first single-precision step.
    try {
        simd_variant();
    } catch (const std::runtime_error& e) {
        throw InputError("environment", "SPHCLIP_SIMD", e.what());
    }
    if (scene.dimension == 3 &&
        std::find(options.exports.begin(), options.exports.end(), "surface") !=
            options.exports.end() &&
        !surface_3d_available())
        throw InputError("command line", "--export",
                         "surface in 3D needs OpenVDB: " + surface_3d_unavailable_reason());
    const fs::path folder = recorded      ? rerun_folder(options, scene)
                            : options.out ? *options.out
                                          : output_folder(scene);
    // Over MPI ranks (docs/mpi.md) rank 0 writes every output; the others
    // step with it and write nothing, not even the folder.
    if (!parallel::leader()) {
        if (options.threads > 0)
            omp_set_num_threads(options.threads);
        return run_clip(scene, folder, options, nullptr);
    }
    if (options.rerun_of && !options.quiet) {
        say("sphclip: re-running {} (sphclip {}, commit {}, started {})\n", options.scene->string(),
            options.rerun_of->sphclip_version, options.rerun_of->git_commit,
            options.rerun_of->started_utc);
        if (options.rerun_of->git_commit != build_git_commit())
            say("sphclip: note: this sphclip is commit {}; a different build may give "
                "different state hashes\n",
                build_git_commit());
    }
    // The GL context before any output: when none can be made, nothing is written.
    std::unique_ptr<GlContext> gl_context;
    if (options.png || options.mp4)
        gl_context = options.backend.empty() ? make_gl_context(scene.render.backend)
                                             : make_gl_context(std::string_view(options.backend));
    // The 3D surface's OpenVDB module, loaded here too (the scene check
    // knows only whether the build has it).
    if ((options.png || options.mp4) && scene.dimension == 3 &&
        scene.render.style == FluidStyle::surface && !surface_3d_available())
        throw InputError(scene.file, "render.style",
                         "surface in 3D needs OpenVDB: " + surface_3d_unavailable_reason());
    // The MP4's encoder too (FFmpeg is loaded here, not at start:
    // platform/shared_library.hpp): without it, nothing is written.
    if (options.mp4)
        if (const std::string problem = Mp4Writer::unavailable_reason(); !problem.empty())
            throw std::runtime_error("cannot write clip.mp4: " + problem +
                                     " (--no-mp4 runs need no FFmpeg)");
    // Over MPI ranks, depth compositing asked for where it cannot draw.
    if (parallel::size() > 1 && (options.png || options.mp4) &&
        scene.render.mpi_composite == MpiComposite::depth)
        if (const std::string problem = depth_composite_problem(scene); !problem.empty())
            throw InputError(scene.file, "render.mpi_composite", problem);
    if (gl_context) {
        // A frame the context cannot draw is known now, before any output.
        const RenderSettings settings = make_render_settings(scene);
        const std::string problem =
            frame_size_problem(*gl_context, settings.width, settings.height, settings.samples);
        if (!problem.empty())
            throw InputError(scene.file, "render.size", problem);
        // A font the user named and FreeType cannot use (a FIFO would block).
        if (!settings.font.empty())
            if (const std::string font = font_problem(settings.font); !font.empty())
                throw InputError(scene.file, "render.font", font);
    }
    // A stop asked for while the run was being set up: nothing is written.
    if (const int signal = StopSignals::received()) {
        say(stderr,
            "sphclip: stopped by signal {} before the run started; nothing "
            "written\n",
            signal);
        return parallel::end_job(exit_interrupted);
    }
    // Held until the run ends: no other run writes into the folder meanwhile.
    const OutputFolder output(folder);
    if (!output.replaced().empty() && !options.quiet)
        say("sphclip: replacing the earlier run in {}: removed {}\n", folder.string(),
            fmt::join(output.replaced(), ", "));
    if (options.threads > 0)
        omp_set_num_threads(options.threads);
    return run_clip(scene, folder, options, std::move(gl_context));
}

} // namespace sph
