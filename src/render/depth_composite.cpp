#include "render/depth_composite.hpp"

#include <embedded_shaders.hpp>
#include <stdexcept>

namespace sph {

namespace {

// The units the layer passes read from: 0-2 hold the colour map, the shadow
// map and the ambient occlusion's depth.
constexpr GLint colour_unit = 3, depth_bits_unit = 4;

void flat_texture(const gl::Texture& texture, GLenum format, int width, int height) {
    glBindTexture(GL_TEXTURE_2D, texture.id());
    glTexStorage2D(GL_TEXTURE_2D, 1, format, width, height);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

void bind_units(GLuint colour, GLuint depth_bits, GLenum target) {
    glActiveTexture(GL_TEXTURE0 + colour_unit);
    glBindTexture(target, colour);
    glActiveTexture(GL_TEXTURE0 + depth_bits_unit);
    glBindTexture(target, depth_bits);
    glActiveTexture(GL_TEXTURE0);
}

void set_units(const gl::Program& program, int samples) {
    const GLuint id = program.id();
    glProgramUniform1i(id, glGetUniformLocation(id, "u_colour"), colour_unit);
    glProgramUniform1i(id, glGetUniformLocation(id, "u_depth_bits"), depth_bits_unit);
    glProgramUniform1i(id, glGetUniformLocation(id, "u_samples"), samples);
}

} // namespace

bool layer_fits(int width, int samples) {
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    return std::int64_t(width) * samples <= max_size;
}

RankLayer::RankLayer(int width, int height, int samples)
    : width_(width), height_(height), samples_(samples), colour_(gl::Texture::generate()),
      depth_bits_(gl::Texture::generate()), depth_(gl::Renderbuffer::generate()),
      framebuffer_(gl::Framebuffer::generate()), flat_colour_(gl::Texture::generate()),
      flat_depth_bits_(gl::Texture::generate()), flat_framebuffer_(gl::Framebuffer::generate()),
      unpack_(gl::link_program(shaders::fullscreen_vert, shaders::layer_unpack_frag, "")),
      vao_(gl::VertexArray::generate()) {
    // Fixed sample locations, as the frame's renderbuffers have them.
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, colour_.id());
    glTexStorage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_RGBA8, width, height, GL_TRUE);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, depth_bits_.id());
    glTexStorage2DMultisample(GL_TEXTURE_2D_MULTISAMPLE, samples, GL_R32UI, width, height, GL_TRUE);
    glBindTexture(GL_TEXTURE_2D_MULTISAMPLE, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D_MULTISAMPLE,
                           colour_.id(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D_MULTISAMPLE,
                           depth_bits_.id(), 0);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
    const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, both);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the rank's layer framebuffer is incomplete");

    flat_texture(flat_colour_, GL_RGBA8, width * samples, height);
    flat_texture(flat_depth_bits_, GL_R32UI, width * samples, height);
    glBindFramebuffer(GL_FRAMEBUFFER, flat_framebuffer_.id());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, flat_colour_.id(),
                           0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D,
                           flat_depth_bits_.id(), 0);
    glDrawBuffers(2, both);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the rank's flat layer framebuffer is incomplete");
    set_units(unpack_, samples);
    gl::check_gl("rank layer set-up");
}

void RankLayer::begin() {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
    const GLfloat none[4] = {0, 0, 0, 0};
    const GLuint empty[4] = {empty_sample, 0, 0, 0};
    const GLfloat far = 1.f;
    glClearBufferfv(GL_COLOR, 0, none);
    glClearBufferuiv(GL_COLOR, 1, empty);
    glClearBufferfv(GL_DEPTH, 0, &far);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_MULTISAMPLE);
}

void RankLayer::flatten() {
    glBindFramebuffer(GL_FRAMEBUFFER, flat_framebuffer_.id());
    glViewport(0, 0, width_ * samples_, height_);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(unpack_.id());
    glBindVertexArray(vao_.id());
    bind_units(colour_.id(), depth_bits_.id(), GL_TEXTURE_2D_MULTISAMPLE);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glEnable(GL_DEPTH_TEST);
}

void RankLayer::read(RankLayerPixels& out) const {
    const std::size_t samples = std::size_t(width_) * std::size_t(samples_) * std::size_t(height_);
    out.colour.resize(samples * 4);
    out.depth_bits.resize(samples);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, flat_framebuffer_.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, width_ * samples_, height_, GL_RGBA, GL_UNSIGNED_BYTE, out.colour.data());
    glReadBuffer(GL_COLOR_ATTACHMENT1);
    glReadPixels(0, 0, width_ * samples_, height_, GL_RED_INTEGER, GL_UNSIGNED_INT,
                 out.depth_bits.data());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    gl::check_gl("reading the rank's layer");
}

LayerImport::LayerImport(int width, int height, int samples)
    : width_(width), height_(height), samples_(samples),
      program_(gl::link_program(shaders::fullscreen_vert, shaders::layer_import_frag, "")),
      vao_(gl::VertexArray::generate()) {
    set_units(program_, samples);
}

FlatLayer LayerImport::upload(std::size_t slot, const RankLayerPixels& layer) {
    while (colour_.size() <= slot) {
        colour_.push_back(gl::Texture::generate());
        flat_texture(colour_.back(), GL_RGBA8, width_ * samples_, height_);
        depth_bits_.push_back(gl::Texture::generate());
        flat_texture(depth_bits_.back(), GL_R32UI, width_ * samples_, height_);
    }
    const std::size_t samples = std::size_t(width_) * std::size_t(samples_) * std::size_t(height_);
    if (layer.colour.size() != samples * 4 || layer.depth_bits.size() != samples)
        throw std::runtime_error("a rank's layer has the wrong size");
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glBindTexture(GL_TEXTURE_2D, colour_[slot].id());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_ * samples_, height_, GL_RGBA, GL_UNSIGNED_BYTE,
                    layer.colour.data());
    glBindTexture(GL_TEXTURE_2D, depth_bits_[slot].id());
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_ * samples_, height_, GL_RED_INTEGER,
                    GL_UNSIGNED_INT, layer.depth_bits.data());
    return {colour_[slot].id(), depth_bits_[slot].id()};
}

void LayerImport::draw(std::span<const FlatLayer> layers, std::uint32_t group_bit) const {
    glViewport(0, 0, width_, height_);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glUseProgram(program_.id());
    glUniform1ui(glGetUniformLocation(program_.id(), "u_group_bit"), group_bit);
    glBindVertexArray(vao_.id());
    for (const FlatLayer& layer : layers) {
        bind_units(layer.colour, layer.depth_bits, GL_TEXTURE_2D);
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }
}

} // namespace sph
