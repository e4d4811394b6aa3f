#pragma once
// Ways of drawing the spheres that the render benchmark measures beside the
// renderer's own (tests/bench/render_bench.cpp), and that no scene can ask
// for: flat discs for small spheres, as instanced triangles or as point
// sprites; a front-to-back order; conservative depth. Built here from the
// renderer's parts (src/render/), so the product keeps only what scenes use.

#include "output/image.hpp"
#include "render/frame_renderer.hpp"
#include "render/render_settings.hpp"
#include "sph/snapshot.hpp"

#include <cstddef>
#include <memory>

namespace sph {

struct DrawVariant {
    // Impostors whose image is narrower than this (px) are drawn as flat,
    // lit discs facing the eye at the sphere's front: no ray cast and no
    // depth written, so llvmpipe can test depth before shading. 0: never.
    double flat_below_px = 0;
    // Flat discs as point sprites, one vertex each, not instanced triangles.
    // A point is dropped whole once its centre leaves the view, so only
    // spheres wholly inside the view (known when culling) become points.
    bool flat_as_points = false;
    // Draw the spheres roughly front to back (by a coarse depth key), so the
    // depth test rejects the hidden ones' fragments.
    bool sort_front_to_back = false;
    // Declare the impostors' depth `depth_greater` (ARB_conservative_depth),
    // drawing each outline at its sphere's front.
    bool conservative_depth = false;
};

// The renderer's frame (FrameRenderer) drawn with a variant: with none, the
// same pixels.
class VariantRenderer {
  public:
    // Needs a current GL 4.5 context; throws std::runtime_error on GL errors.
    VariantRenderer(const RenderSettings& settings, const DrawVariant& variant);
    ~VariantRenderer();
    VariantRenderer(const VariantRenderer&) = delete;
    VariantRenderer& operator=(const VariantRenderer&) = delete;

    Image render(const Snapshot& frame);
    const FrameTimings& last_timings() const { return timings_; }
    // As FrameRenderer's, and the spheres of the last frame drawn as flat discs.
    std::size_t last_drawn() const;
    std::size_t last_flat() const;
    std::size_t last_outside_view() const;
    const RenderSettings& settings() const { return settings_; }
    const DrawVariant& variant() const { return variant_; }

  private:
    struct Parts;
    RenderSettings settings_;
    DrawVariant variant_;
    std::unique_ptr<Parts> parts_;
    FrameTimings timings_;
};

} // namespace sph
