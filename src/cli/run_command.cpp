#include "cli/run_command.hpp"

#include "cli/clip_run.hpp"
#include "io/input_error.hpp"
#include "render/gl_context.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <memory>
#include <omp.h>
#include <unistd.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

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

// Half the size, rounded to even (yuv420p needs even sizes, so the video is
// not padded), and libx264's fastest preset. run.json's scene records both.
void make_fast_preview(Scene& scene) {
    for (int& side : scene.render.size)
        side = 2 * std::max(1, (side + 2) / 4);
    scene.render.video_preset = "ultrafast";
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
    return run_clip(scene, folder, options, std::move(gl_context));
}

} // namespace sph
