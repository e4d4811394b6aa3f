#include "output/surface_export.hpp"

#include "output/files.hpp"
#include "output/particle_export.hpp"
#include "render/colour_maps.hpp"
#include "render/surface/reconstruct.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>

namespace sph {

namespace {

static_assert(std::endian::native == std::endian::little,
              "the PLY writer writes the machine's bytes as little-endian");

template <class T>
void append(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

std::string scalar_name(ColourField field) {
    return field == ColourField::velocity ? "speed" : choice_name(field);
}

} // namespace

std::string ply_bytes(const SurfaceMesh& mesh, const std::string& name, ColourMap colour_map,
                      std::array<double, 2> range) {
    const std::vector<Rgb8> table = colour_map_table(colour_map);
    const std::size_t nv = mesh.vertices(), nf = mesh.triangles.size() / 3;
    std::string out = fmt::format("ply\n"
                                  "format binary_little_endian 1.0\n"
                                  "comment sphclip fluid surface, SI units\n"
                                  "element vertex {}\n"
                                  "property float x\nproperty float y\nproperty float z\n"
                                  "property float nx\nproperty float ny\nproperty float nz\n"
                                  "property float {}\n"
                                  "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                                  "element face {}\n"
                                  "property list uchar int vertex_indices\n"
                                  "end_header\n",
                                  nv, name, nf);
    out.reserve(out.size() + nv * 31 + nf * 13);
    for (std::size_t v = 0; v < nv; ++v) {
        for (int a = 0; a < 3; ++a)
            append(out, mesh.positions[3 * v + a]);
        for (int a = 0; a < 3; ++a)
            append(out, mesh.normals[3 * v + a]);
        append(out, mesh.scalar[v]);
        // The texture's lookup (nearest of 256, clamped at the ends).
        const double t = (mesh.scalar[v] - range[0]) / std::max(range[1] - range[0], 1e-300);
        const Rgb8& rgb = table[std::size_t(std::clamp(t, 0.0, 1.0) * 255 + 0.5)];
        for (std::uint8_t c : rgb)
            append(out, c);
    }
    for (std::size_t f = 0; f < nf; ++f) {
        append(out, std::uint8_t(3));
        for (int k = 0; k < 3; ++k)
            append(out, std::int32_t(mesh.triangles[3 * f + k]));
    }
    return out;
}

SurfaceExport::SurfaceExport(std::filesystem::path folder, const RenderSettings& settings,
                             std::shared_ptr<FrameSurface> surface)
    : folder_(std::move(folder)), settings_(settings),
      surface_(surface ? std::move(surface)
                       : std::make_shared<FrameSurface>(settings.field, settings.spacing,
                                                        settings.surface)) {
    std::filesystem::create_directories(folder_ / "surface");
}

void SurfaceExport::write(const Snapshot& frame) {
    const Surface& surface = surface_->of(frame);
    const std::filesystem::path stem = folder_ / "surface" / frame_stem(frame.frame);
    if (surface.level_set)
        write_level_set(*surface.level_set, std::filesystem::path(stem) += ".vdb");
    write_file_atomically(std::filesystem::path(stem) += ".ply",
                          ply_bytes(surface.mesh, scalar_name(settings_.field),
                                    settings_.colour_map, settings_.range));
}

} // namespace sph
