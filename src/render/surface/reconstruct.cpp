#include "render/surface/reconstruct.hpp"

#include "render/surface/vertex_colours.hpp"
#include "sph/wall_clock.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace sph {

std::vector<float> particle_scalars(const Snapshot& frame, ColourField field) {
    const std::size_t n = frame.size();
    const int dim = frame.dimension;
    std::vector<float> out(n);
    if (field == ColourField::velocity) {
        for (std::size_t i = 0; i < n; ++i) {
            double v2 = 0;
            for (int a = 0; a < dim; ++a)
                v2 += frame.velocity[i * dim + a] * frame.velocity[i * dim + a];
            out[i] = float(std::sqrt(v2));
        }
    } else {
        const std::vector<Real>& values =
            field == ColourField::density ? frame.density : frame.pressure;
        for (std::size_t i = 0; i < n && i < values.size(); ++i)
            out[i] = float(values[i]);
    }
    return out;
}

Surface reconstruct_surface(const Snapshot& frame, ColourField field, double spacing,
                            const SurfaceSettings& settings) {
    Surface s;
    const auto start = Clock::now();
    const std::vector<float> scalars = particle_scalars(frame, field);
    if (frame.dimension == 2) {
        // The grid carries the colour too: one pass does both.
        s.mesh = reconstruct_region_2d(frame, scalars, spacing, settings);
        s.reconstruction_seconds = seconds_since(start);
        return s;
    }
    if (!surface_3d_available())
        throw std::runtime_error("a surface in 3D needs OpenVDB: " +
                                 surface_3d_unavailable_reason());
    s.level_set = make_level_set(frame, spacing, settings, &s.steps);
    s.mesh = mesh_level_set(*s.level_set, &s.steps);
    s.reconstruction_seconds = seconds_since(start);
    const auto colour_start = Clock::now();
    // The SPH support of the seed kernel: two spacings.
    colour_vertices(s.mesh, frame, scalars, 2 * spacing);
    s.colour_seconds = seconds_since(colour_start);
    return s;
}

} // namespace sph
