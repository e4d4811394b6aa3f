// reconstruct.hpp's 3D functions, forwarded to libsphclip_vdb.so
// (level_set_module.hpp), loaded on first use.
#include "render/surface/level_set_module.hpp"

#include "platform/shared_library.hpp"

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>

namespace sph {

namespace {

// Beside the program (installed, and build/libexec/sphclip/ in a build);
// else where the build put it, for the tests' programs in other folders.
std::string module_path() {
    std::error_code error;
    const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
    if (!error) {
        const std::filesystem::path beside = self.parent_path() / "libsphclip_vdb.so";
        if (std::filesystem::exists(beside, error))
            return beside.string();
    }
    return SPHCLIP_VDB_MODULE_IN_BUILD;
}

const LevelSetFunctions& level_set_functions() {
    static const LevelSetFunctions* const functions = [] {
        const std::string path = module_path();
        using Entry = const LevelSetFunctions* (*)();
        return library_function<Entry>(path, level_set_entry)();
    }();
    return *functions;
}

} // namespace

bool surface_3d_available() {
    return surface_3d_unavailable_reason().empty();
}

std::string surface_3d_unavailable_reason() {
    try {
        level_set_functions();
        return "";
    } catch (const std::runtime_error& e) {
        return e.what(); // the module and the loader's reason
    }
}

std::shared_ptr<const LevelSet> make_level_set(const Snapshot& frame, double spacing,
                                               const SurfaceSettings& settings,
                                               SurfaceSteps* steps) {
    return level_set_functions().make_level_set(frame, spacing, settings, steps);
}

SurfaceMesh mesh_level_set(const LevelSet& level_set, SurfaceSteps* steps) {
    return level_set_functions().mesh_level_set(level_set, steps);
}

void write_level_set(const LevelSet& level_set, const std::filesystem::path& path) {
    level_set_functions().write_level_set(level_set, path);
}

} // namespace sph
