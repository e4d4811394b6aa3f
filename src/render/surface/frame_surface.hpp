#pragma once
// One frame's surface for every consumer of that frame: with render.style =
// surface and `--export surface` both on, the picture and the export are
// the same mesh, reconstructed once (the reconstruction costs far more than
// drawing or writing it, docs/benchmarks.md).

#include "render/surface/reconstruct.hpp"

#include <cstdint>
#include <optional>
#include <string>

namespace sph {

class FrameSurface {
  public:
    // The colour field, the particle spacing (m) and the render.surface keys
    // every consumer shares.
    FrameSurface(ColourField field, double spacing, const SurfaceSettings& settings);

    // The surface of `frame`: reconstructed at the first call for that frame
    // (its number and step count), the same surface at the next calls.
    // Throws as reconstruct_surface does.
    const Surface& of(const Snapshot& frame);
    // How many times a surface was reconstructed.
    std::size_t reconstructions() const { return reconstructions_; }

  private:
    ColourField field_;
    double spacing_;
    SurfaceSettings settings_;
    struct Key {
        std::uint64_t frame, steps;
        bool operator==(const Key&) const = default;
    };
    std::optional<Key> key_;
    Surface surface_;
    std::size_t reconstructions_ = 0;
};

} // namespace sph
