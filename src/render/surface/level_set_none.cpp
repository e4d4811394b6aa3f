// The build without OpenVDB: no 3D surface (reconstruct.hpp). The scene check
// refuses render.style = surface in 3D before a run starts (exit 2); these
// are only reached by a caller that skipped it.
#include "render/surface/reconstruct.hpp"

#include <stdexcept>

namespace sph {

class LevelSet {};

namespace {
[[noreturn]] void no_openvdb() {
    throw std::runtime_error("this sphclip was built without OpenVDB: no 3D surface");
}
} // namespace

bool surface_3d_available() {
    return false;
}
std::string surface_3d_unavailable_reason() {
    return "this sphclip was built without OpenVDB (install libopenvdb-dev and configure with "
           "-DSPHCLIP_OPENVDB=ON)";
}
std::shared_ptr<const LevelSet> make_level_set(const Snapshot&, double, const SurfaceSettings&,
                                               SurfaceSteps*) {
    no_openvdb();
}
SurfaceMesh mesh_level_set(const LevelSet&, SurfaceSteps*) {
    no_openvdb();
}
void write_level_set(const LevelSet&, const std::filesystem::path&) {
    no_openvdb();
}

} // namespace sph
