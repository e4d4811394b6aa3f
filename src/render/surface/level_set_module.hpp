#pragma once
// The 3D surface's OpenVDB part (level_set_vdb.cpp) is a module of its own,
// libsphclip_vdb.so beside the program proper, loaded when a run first
// reconstructs a 3D surface: OpenVDB (with TBB, Boost and its codecs) cost
// every start 0.05 s in the dynamic loader (platform/shared_library.hpp).
// level_set_module.cpp loads it and forwards reconstruct.hpp's 3D functions
// to the table it exports.

#include "render/surface/reconstruct.hpp"

#include <filesystem>
#include <memory>

namespace sph {

struct LevelSetFunctions {
    std::shared_ptr<const LevelSet> (*make_level_set)(const Snapshot&, double,
                                                      const SurfaceSettings&, SurfaceSteps*);
    SurfaceMesh (*mesh_level_set)(const LevelSet&, SurfaceSteps*);
    void (*write_level_set)(const LevelSet&, const std::filesystem::path&);
};

// The module's one exported symbol: extern "C" const LevelSetFunctions* NAME().
inline constexpr const char* level_set_entry = "sphclip_level_set_functions";

} // namespace sph
