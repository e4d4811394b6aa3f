#include "render/light_rig.hpp"

namespace sph {

LightRig::LightRig(const RenderSettings& s, double reach)
    : up_(s.up), palette_(palette(s.background)), reach_(reach),
      // A penumbra of about a sphere and a half: soft enough that a single
      // layer's shadow reads as one sheet, not as dots.
      softness_(1.5 * s.radius) {
    if (casts_shadows(s))
        shadow_map_.emplace(shadow_map_size(reach, s.radius));
    // Occluders count within four sphere radii: the creases between
    // neighbours and the first layer behind the surface.
    if (s.dimension == 3 && s.ambient_occlusion)
        occlusion_.emplace(s.width, s.height, 4 * s.radius);
}

Lighting LightRig::light(const Camera& camera, const std::vector<ShadowMap::DrawDepth>& casters) {
    Lighting lighting = key_light(camera, up_, palette_);
    if (shadow_map_ && !camera.orthographic) {
        shadow_map_->render(camera, reach_, softness_, lighting, casters);
        if (combine_)
            shadow_map_->combine(combine_);
        shadow_map_->bind();
    }
    return lighting;
}

void LightRig::occlude(const gl::RenderTarget& target, const Camera& camera) {
    if (occlusion_ && !camera.orthographic)
        occlusion_->apply(target, camera);
}

} // namespace sph
