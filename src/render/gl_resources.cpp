#include "render/gl_resources.hpp"

#include "render/colour_maps.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <stdexcept>
#include <utility>
#include <vector>

namespace sph::gl {

GLuint generate_object(Kind kind) {
    GLuint id = 0;
    switch (kind) {
    case Kind::program:
        id = glCreateProgram();
        break;
    case Kind::buffer:
        glGenBuffers(1, &id);
        break;
    case Kind::vertex_array:
        glGenVertexArrays(1, &id);
        break;
    case Kind::texture:
        glGenTextures(1, &id);
        break;
    case Kind::renderbuffer:
        glGenRenderbuffers(1, &id);
        break;
    case Kind::framebuffer:
        glGenFramebuffers(1, &id);
        break;
    }
    return id;
}

void delete_object(Kind kind, GLuint id) {
    if (id == 0)
        return;
    switch (kind) {
    case Kind::program:
        glDeleteProgram(id);
        break;
    case Kind::buffer:
        glDeleteBuffers(1, &id);
        break;
    case Kind::vertex_array:
        glDeleteVertexArrays(1, &id);
        break;
    case Kind::texture:
        glDeleteTextures(1, &id);
        break;
    case Kind::renderbuffer:
        glDeleteRenderbuffers(1, &id);
        break;
    case Kind::framebuffer:
        glDeleteFramebuffers(1, &id);
        break;
    }
}

namespace {

// A compiled shader, deleted when it goes (once linked, the program keeps it).
struct Shader {
    explicit Shader(GLuint shader) : id(shader) {}
    Shader(Shader&& other) noexcept : id(std::exchange(other.id, 0)) {}
    Shader& operator=(Shader&&) = delete;
    ~Shader() {
        if (id != 0)
            glDeleteShader(id);
    }
    GLuint id;
};

Shader compile(GLenum stage, std::string_view common, std::string_view body) {
    const std::string source = "#version 450 core\n" + std::string(common) + std::string(body);
    Shader shader{glCreateShader(stage)};
    const char* text = source.c_str();
    glShaderSource(shader.id, 1, &text, nullptr);
    glCompileShader(shader.id);
    GLint ok = 0;
    glGetShaderiv(shader.id, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(shader.id, sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader compilation failed: ") + log);
    }
    return shader;
}

} // namespace

Program link_program(std::string_view vertex, std::string_view fragment, std::string_view common) {
    const Shader vs = compile(GL_VERTEX_SHADER, common, vertex);
    const Shader fs = compile(GL_FRAGMENT_SHADER, common, fragment);
    Program program = Program::generate();
    glAttachShader(program.id(), vs.id);
    glAttachShader(program.id(), fs.id);
    glLinkProgram(program.id());
    GLint ok = 0;
    glGetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetProgramInfoLog(program.id(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string("shader link failed: ") + log);
    }
    return program;
}

void check_gl(const char* where) {
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
        throw std::runtime_error(fmt::format("OpenGL error 0x{:04x} in {}", error, where));
}

Texture make_colour_map_texture(ColourMap map) {
    const auto table = colour_map_table(map, 256);
    Texture texture = Texture::generate();
    glBindTexture(GL_TEXTURE_1D, texture.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage1D(GL_TEXTURE_1D, 0, GL_RGB8, 256, 0, GL_RGB, GL_UNSIGNED_BYTE, table.data());
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_1D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    return texture;
}

void bind_colour_map(const Texture& texture) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_1D, texture.id());
}

RenderTarget::RenderTarget(int width, int height, int samples)
    : width_(width), height_(height), msaa_colour_(Renderbuffer::generate()),
      msaa_depth_(Renderbuffer::generate()), resolve_colour_(Renderbuffer::generate()),
      msaa_(Framebuffer::generate()), resolve_(Framebuffer::generate()) {
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_colour_.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    glBindRenderbuffer(GL_RENDERBUFFER, msaa_depth_.id());
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              msaa_colour_.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER,
                              msaa_depth_.id());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the multisampled framebuffer is incomplete");
    glBindRenderbuffer(GL_RENDERBUFFER, resolve_colour_.id());
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, resolve_.id());
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER,
                              resolve_colour_.id());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw std::runtime_error("the resolve framebuffer is incomplete");
}

void RenderTarget::begin() {
    glBindFramebuffer(GL_FRAMEBUFFER, msaa_.id());
    glViewport(0, 0, width_, height_);
    glClearColor(background[0], background[1], background[2], 1.f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glEnable(GL_MULTISAMPLE);
}

Image RenderTarget::read() const {
    const int w = width_, h = height_;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, msaa_.id());
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, resolve_.id());
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, resolve_.id());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    Image image(w, h);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    // GL's rows run bottom-up.
    const std::size_t row = std::size_t(w) * 4;
    std::vector<std::uint8_t> swap(row);
    for (int y = 0; y < h / 2; ++y) {
        std::uint8_t* a = image.rgba.data() + std::size_t(y) * row;
        std::uint8_t* b = image.rgba.data() + std::size_t(h - 1 - y) * row;
        std::copy(a, a + row, swap.data());
        std::copy(b, b + row, a);
        std::copy(swap.begin(), swap.end(), b);
    }
    return image;
}

} // namespace sph::gl
