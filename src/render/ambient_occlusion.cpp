#include "render/ambient_occlusion.hpp"

#include <embedded_shaders.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>

namespace sph {

namespace {

// The unit the passes read their textures from: 0 and 1 hold the colour and
// shadow maps.
constexpr GLint unit = 2;

void make_texture(const gl::Texture& texture, GLenum format, int width, int height) {
    glBindTexture(GL_TEXTURE_2D, texture.id());
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

} // namespace

AmbientOcclusion::AmbientOcclusion(int width, int height, double reach)
    : width_(width), height_(height), reach_(float(reach)),
      occlusion_program_(
          gl::link_program(shaders::fullscreen_vert, shaders::ambient_occlusion_frag, "")),
      apply_program_(
          gl::link_program(shaders::fullscreen_vert, shaders::ambient_occlusion_apply_frag, "")),
      vao_(gl::VertexArray::generate()), depth_(gl::Texture::generate()),
      occlusion_(gl::Texture::generate()), depth_framebuffer_(gl::Framebuffer::generate()),
      occlusion_framebuffer_(gl::Framebuffer::generate()) {
    // The render target's depth format, as a blit from it needs.
    make_texture(depth_, GL_DEPTH_COMPONENT24, width, height);
    make_texture(occlusion_, GL_R8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, depth_framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.id(), 0);
    glDrawBuffer(GL_NONE);
    glReadBuffer(GL_NONE);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the ambient occlusion's depth framebuffer is incomplete");
    glBindFramebuffer(GL_FRAMEBUFFER, occlusion_framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, occlusion_.id(), 0);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the ambient occlusion's framebuffer is incomplete");
    for (const GLuint id : {occlusion_program_.id(), apply_program_.id()}) {
        glProgramUniform1i(id, glGetUniformLocation(id, "u_depth"), unit);
        glProgramUniform1i(id, glGetUniformLocation(id, "u_occlusion"), unit);
    }
}

void AmbientOcclusion::apply(const gl::RenderTarget& target, const Camera& camera) {
    // The depth, one sample a pixel.
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, depth_framebuffer_.id());
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_DEPTH_BUFFER_BIT,
                      GL_NEAREST);

    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(vao_.id());
    glActiveTexture(GL_TEXTURE0 + unit);
    // The occlusion.
    glBindFramebuffer(GL_FRAMEBUFFER, occlusion_framebuffer_.id());
    glViewport(0, 0, width_, height_);
    glBindTexture(GL_TEXTURE_2D, depth_.id());
    const GLuint program = occlusion_program_.id();
    glUseProgram(program);
    const glm::mat4 inverse = glm::inverse(camera.projection);
    glUniformMatrix4fv(glGetUniformLocation(program, "u_inverse_projection"), 1, GL_FALSE,
                       glm::value_ptr(inverse));
    glUniform1f(glGetUniformLocation(program, "u_reach"), reach_);
    glUniform1f(glGetUniformLocation(program, "u_focal_px"),
                0.5f * camera.projection[1][1] * float(height_));
    glUniform1f(glGetUniformLocation(program, "u_strength"), 1.0f);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    // The frame times the filtered occlusion, every sample of a pixel alike.
    glBindFramebuffer(GL_FRAMEBUFFER, target.framebuffer());
    glBindTexture(GL_TEXTURE_2D, occlusion_.id());
    glUseProgram(apply_program_.id());
    glEnable(GL_BLEND);
    glBlendFunc(GL_ZERO, GL_SRC_COLOR);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glActiveTexture(GL_TEXTURE0);
    glEnable(GL_DEPTH_TEST);
}

} // namespace sph
