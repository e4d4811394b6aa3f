#pragma once
// Per-frame fluid surfaces for Blender or ParaView (`--export surface`):
//   surface/frame_NNNNN.ply  the mesh, binary little-endian PLY: float x, y,
//                            z (m), nx, ny, nz (unit, out of the fluid), the
//                            colour field (speed m/s, density kg/m^3 or
//                            pressure Pa, named so) and uchar red, green,
//                            blue (the field through the frames' colour map
//                            and range, which every PLY viewer shows) per
//                            vertex; triangles as lists of int vertex_indices
//   surface/frame_NNNNN.vdb  3D: the level set it was meshed from, an
//                            OpenVDB FloatGrid named "surface" (signed
//                            distance, m; negative inside the fluid)
// The surface is the one render.style = surface draws, from the scene's
// render.surface keys (render/surface/reconstruct.hpp). Each file is written
// whole through a temporary, or not at all.

#include "output/frame_sink.hpp"
#include "render/render_settings.hpp"
#include "render/surface/frame_surface.hpp"
#include "render/surface/surface_mesh.hpp"

#include <filesystem>
#include <memory>
#include <string>

namespace sph {

class SurfaceExport final : public FrameSink {
  public:
    // Frames go to folder/surface/; the field, colour map, range, spacing
    // and surface keys from the render settings. `surface`: the frame's
    // surface, shared with the renderer (render.style = surface) so that it
    // is reconstructed once; made from `settings`, it is the same surface.
    SurfaceExport(std::filesystem::path folder, const RenderSettings& settings,
                  std::shared_ptr<FrameSurface> surface = nullptr);
    void write(const Snapshot& frame) override;
    FrameFields fields() const override {
        return {.pressure = settings_.field == ColourField::pressure};
    }

  private:
    std::filesystem::path folder_;
    RenderSettings settings_;
    std::shared_ptr<FrameSurface> surface_;
};

// The mesh as a binary little-endian PLY file, the scalar named `scalar_name`,
// each vertex's colour `colour_map` at its scalar within `range`.
std::string ply_bytes(const SurfaceMesh& mesh, const std::string& scalar_name, ColourMap colour_map,
                      std::array<double, 2> range);

} // namespace sph
