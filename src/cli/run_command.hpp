#pragma once
// `sphclip run`: scene -> simulation -> per-frame outputs.

#include "io/scene.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace sph {

struct RunOptions {
    std::optional<std::filesystem::path> scene; // none: the built-in scene
    std::optional<std::filesystem::path> out;   // none: out/<scene name>/
    std::vector<Override> overrides;            // --set, then --duration, --fps
    int threads = 0;                            // 0: all cores
    std::vector<std::string> exports;           // "csv", "vtk", "vtk-ascii"
    bool png = true;
    bool mp4 = true;
    bool quiet = false;
    // Half the image size (rounded to even) and the fastest x264 preset.
    bool fast_preview = false;
    std::string backend; // --backend; empty: the scene's render.backend
    std::string command_line; // recorded in run.json
};

// Returns the process exit code; throws InputError for bad input.
int run_command(const RunOptions& options);

} // namespace sph
