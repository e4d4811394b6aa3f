#include "render/shadow_pass.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <stdexcept>

namespace sph {

int shadow_map_size(double reach, double radius) {
    const double texels = 3.0 * 2.0 * reach / std::max(radius, 1e-12);
    // A power of two, rounded up.
    int size = 512;
    while (size < 2048 && size < texels)
        size *= 2;
    return size;
}

ShadowMap::ShadowMap(int size)
    : size_(size), depth_(gl::Texture::generate()), framebuffer_(gl::Framebuffer::generate()) {
    glBindTexture(GL_TEXTURE_2D, depth_.id());
    glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, size, size, 0, GL_DEPTH_COMPONENT,
                 GL_UNSIGNED_INT, nullptr);
    // Compared in the lookup, filtered 2x2 by the hardware; outside the map
    // everything is lit (the border is the far plane).
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    const float border[4] = {1, 1, 1, 1};
    glTexParameterfv(GL_TEXTURE_2D, GL_TEXTURE_BORDER_COLOR, border);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.id(), 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the shadow map's framebuffer is incomplete");
}

void ShadowMap::render(const Camera& eye, double reach, double softness, Lighting& lighting,
                       const std::vector<DrawDepth>& casters) {
    const float r = float(reach);
    // The light's direction in the scene, from the eye's view space.
    const glm::mat3 world_from_view = glm::transpose(glm::mat3(eye.view));
    const glm::vec3 to_light = glm::normalize(world_from_view * lighting.to_light);
    const glm::vec3 side = std::abs(to_light.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    Camera light;
    light.origin = eye.origin;
    light.orthographic = true;
    light.image_height = size_;
    light.view = glm::lookAt(2.f * r * to_light, glm::vec3(0), side);
    light.projection = glm::ortho(-r, r, -r, r, 0.f, 4.f * r);

    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, size_, size_);
    glClearDepth(1.0);
    glClear(GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    for (const DrawDepth& draw : casters)
        draw(light);

    // Eye view space to the map's [0,1]^3, a texel and a half nearer the
    // light against acne (the depth spans 4 reach).
    const float texel = 2.f * r / float(size_);
    const glm::mat4 to_unit = glm::translate(glm::mat4(1.f), glm::vec3(0.5f)) *
                              glm::scale(glm::mat4(1.f), glm::vec3(0.5f));
    const glm::mat4 bias =
        glm::translate(glm::mat4(1.f), glm::vec3(0, 0, -1.5f * texel / (4.f * r)));
    lighting.shadows = true;
    lighting.shadow_from_view =
        bias * to_unit * light.projection * light.view * glm::inverse(eye.view);
    lighting.shadow_softness = float(softness) / (2.f * r);
    lighting.shadow_offset = 1.5f * texel;
}

void ShadowMap::combine(const std::function<void(std::span<std::uint32_t>)>& combine) {
    texels_.resize(std::size_t(size_) * std::size_t(size_));
    glBindTexture(GL_TEXTURE_2D, depth_.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    // 24-bit depth as 32-bit integers: k -> k 2^8 + k / 2^16 and back
    // k = v / 2^8, exact both ways (unlike through floats).
    glGetTexImage(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, texels_.data());
    combine(texels_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, size_, size_, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT,
                    texels_.data());
}

void ShadowMap::bind() const {
    glActiveTexture(GL_TEXTURE0 + shadow_map_unit);
    glBindTexture(GL_TEXTURE_2D, depth_.id());
    glActiveTexture(GL_TEXTURE0);
}

} // namespace sph
