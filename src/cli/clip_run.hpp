#pragma once
// One `sphclip run` of a scene as an object (clip_run.cpp, ClipRun): setup
// (the simulation, the sinks the frames go to, run.json), the frame loop,
// and one finish path that every ending goes through (completed, unstable,
// interrupted, failed), so the outputs are always finalised and run.json
// always says how the run ended and where the time went.

#include "cli/run_command.hpp"
#include "render/gl_context.hpp"
#include "scene/scene.hpp"

#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace sph {

// Runs `scene` into `folder` (made and cleared of earlier frames by the
// caller); `gl_context` is null when no PNG or MP4 is asked for. Returns the
// exit code of a run that ended (README, "Exit codes"); rethrows the error of
// a run that failed, after recording it in run.json.
int run_clip(const Scene& scene, const std::filesystem::path& folder, const RunOptions& options,
             std::unique_ptr<GlContext> gl_context);

// Over MPI ranks (docs/mpi.md, "Rendering over ranks"): from how many
// particles a frame is composited by depth (render.mpi_composite; 0:
// always), none when it is drawn whole on rank 0 (one rank, no pictures,
// gather, or auto where depth cannot draw the scene).
std::optional<std::size_t> depth_composite_from(const Scene& scene, const RunOptions& options,
                                                int ranks);
// Why render.mpi_composite = depth cannot draw `scene`; empty when it can.
std::string depth_composite_problem(const Scene& scene);

} // namespace sph
