#pragma once
// The frame's light and depth, as FrameRenderer (and the render benchmark's
// variants, so they end as its frames do) run them around the draws: the
// key light for the camera, the shadow map from the casters' depth
// (render.shadows), and the ambient occlusion over the opaque frame
// (render.ambient_occlusion); both 3D only.

#include "render/ambient_occlusion.hpp"
#include "render/lighting.hpp"
#include "render/render_settings.hpp"
#include "render/shadow_pass.hpp"

#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace sph {

class LightRig {
  public:
    // `reach`: the radius around the domain's centre the shadows cover, m
    // (Scenery::reach).
    LightRig(const RenderSettings& settings, double reach);
    // The frame's light; with shadows, the map rendered from `casters` and
    // bound (before the frame's target is: it leaves its own bound).
    Lighting light(const Camera& camera, const std::vector<ShadowMap::DrawDepth>& casters);
    // Over MPI ranks, the shadow map's depths made every rank's minimum
    // (ShadowMap::combine) in the frames lit while it is set; none: not.
    void combine_shadows(std::function<void(std::span<std::uint32_t>)> combine) {
        combine_ = std::move(combine);
    }
    // With ambient occlusion, the opaque frame in `target` darkened by it.
    void occlude(const gl::RenderTarget& target, const Camera& camera);

  private:
    glm::dvec3 up_;
    const Palette& palette_;
    double reach_, softness_;
    std::optional<ShadowMap> shadow_map_;
    std::optional<AmbientOcclusion> occlusion_;
    std::function<void(std::span<std::uint32_t>)> combine_;
};

} // namespace sph
