#include "cli/run_command.hpp"

#include "cli/clip_run.hpp"
#include "cli/console.hpp"
#include "cli/exit_codes.hpp"
#include "cli/output_folder.hpp"
#include "cli/set_options.hpp"
#include "cli/stop_signals.hpp"
#include "io/input_error.hpp"
#include "render/gl_context.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <fmt/format.h>
#include <memory>
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

} // namespace

CLI::App* add_run_command(CLI::App& app, RunCommandLine& line) {
    RunOptions& run = line.options;
    auto* cmd = app.add_subcommand("run", "Simulate a scene and write its frames.");
    cmd->add_option("scene", line.scene, "Scene file (JSON); none: the built-in 2D dam break");
    cmd->add_option("--out", line.out, "Output folder (default out/<scene name>/)");
    cmd->add_option("--set", line.sets, "Override a scene field: --set solver.dt=2e-4 (repeatable)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    cmd->add_option("--threads", run.threads, "Threads (default: all cores)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--duration", line.duration, "Simulated seconds (same as --set duration=S)")
        ->check(positive_finite_number());
    cmd->add_option("--fps", line.fps, "Frames per second (same as --set fps=N)")
        ->check(positive_finite_number());
    cmd->add_option("--export", run.exports,
                    "Particle data per frame: csv, vtk (binary, compressed) or vtk-ascii")
        ->check(CLI::IsMember({"csv", "vtk", "vtk-ascii"}))
        ->allow_extra_args(false);
    cmd->add_flag("--no-png", line.no_png, "Write no PNG frames");
    cmd->add_flag("--no-mp4", line.no_mp4, "Write no MP4 video");
    cmd->add_flag("--quiet", run.quiet, "No progress line or summary");
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
    return run;
}

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
    // A stop asked for while the run was being set up: nothing is written.
    if (const int signal = StopSignals::received()) {
        say(stderr,
            "sphclip: stopped by signal {} before the run started; nothing "
            "written\n",
            signal);
        return exit_interrupted;
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
