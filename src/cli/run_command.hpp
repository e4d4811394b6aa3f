#pragma once
// `sphclip run`: scene -> simulation -> per-frame outputs.

#include "scene/scene.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace sph {

// The run.json a run reproduces (`sphclip run out/x/run.json`), as its
// run.json "rerun_of" records it.
struct RerunSource {
    std::filesystem::path run_json;
    std::string sphclip_version, git_commit, started_utc; // "unknown" when not recorded
};

struct RunOptions {
    std::optional<std::filesystem::path> scene; // none: the built-in scene
    std::optional<std::filesystem::path> out;   // none: out/<scene name>/
    std::vector<Override> overrides;            // --set, then --duration, --fps
    int threads = 0;                            // 0: all cores
    std::vector<std::string> exports;           // "csv", "vtk", "vtk-ascii"
    bool png = true;
    bool mp4 = true;
    bool quiet = false;
    std::string progress = "auto";   // --progress: auto | bar | lines | none (progress.hpp)
    double progress_interval_s = 10; // between plain progress lines (progress_interval())
    // Half the image size (rounded to even) and the fastest x264 preset.
    bool fast_preview = false;
    std::string backend;      // --backend; empty: the scene's render.backend
    std::string command_line; // recorded in run.json
    // Set by run_command: the scene file's absolute path (run.json
    // "scene_file_absolute"; a re-run keeps the recorded one: mesh files are
    // relative to its folder), and the run.json a re-run reproduces.
    std::string scene_file_absolute;
    std::optional<RerunSource> rerun_of;
};

// `run`'s command line as it is parsed; run_options() makes it RunOptions.
struct RunCommandLine {
    std::string scene, out;        // empty: the built-in scene, out/<scene name>/
    std::vector<std::string> sets; // --set KEY=VALUE
    double duration = 0, fps = 0;  // 0: the scene's
    bool no_png = false, no_mp4 = false;
    RunOptions options; // --threads, --export, --quiet, --fast-preview, --backend
};

// Adds the `run` subcommand to `app`; parsing fills `line`.
CLI::App* add_run_command(CLI::App& app, RunCommandLine& line);

// Throws InputError for a --set that is not KEY=VALUE.
RunOptions run_options(const RunCommandLine& line, const std::string& command_line);

// Returns the process exit code; throws InputError for bad input.
int run_command(const RunOptions& options);

} // namespace sph
