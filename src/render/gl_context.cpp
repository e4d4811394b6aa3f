#include "render/gl_context.hpp"

#include "render/gl_resources.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <glad/gl.h>

namespace sph {

namespace {
// glad hands the loader a name and wants a function pointer back.
void* (*current_get_proc)(const char*) = nullptr;
GLADapiproc load_one(const char* name) {
    return reinterpret_cast<GLADapiproc>(current_get_proc(name));
}
std::string gl_string(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? text : "";
}
} // namespace

void GlContext::load_functions(void* (*get_proc)(const char*), std::string backend) {
    current_get_proc = get_proc;
    const int version = gladLoadGL(load_one);
    if (version == 0)
        throw GlContextError(backend + ": could not load the OpenGL functions");
    if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45)
        throw GlContextError(backend + ": OpenGL 4.5 is needed, the context offers " +
                             std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                             std::to_string(GLAD_VERSION_MINOR(version)));
    info_ = {std::move(backend), gl_string(GL_VENDOR), gl_string(GL_RENDERER),
             gl_string(GL_VERSION)};
    GLint viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &info_.max_renderbuffer_size);
    glGetIntegerv(GL_MAX_SAMPLES, &info_.max_samples);
    info_.max_viewport_width = viewport[0];
    info_.max_viewport_height = viewport[1];
}

std::string frame_size_problem(const GlContext& context, int width, int height, int samples) {
    const GlInfo& gl = context.info();
    const std::string renderer =
        fmt::format("the OpenGL renderer ({}, {})", gl.backend, gl.renderer);
    const int most_width = std::min(gl.max_renderbuffer_size, gl.max_viewport_width);
    const int most_height = std::min(gl.max_renderbuffer_size, gl.max_viewport_height);
    if (width > most_width || height > most_height)
        return fmt::format("{}x{} is larger than {} draws: at most {}x{}", width, height, renderer,
                           most_width, most_height);
    if (samples > gl.max_samples)
        return fmt::format("{} samples a pixel are more than {} offers ({})", samples, renderer,
                           gl.max_samples);
    while (glGetError() != GL_NO_ERROR) {
        // Earlier errors are not this frame's.
    }
    try {
        const gl::RenderTarget probe(width, height, samples);
        // Out of memory shows as an error, not always as an incomplete framebuffer.
        if (glGetError() == GL_OUT_OF_MEMORY)
            throw std::runtime_error("out of memory");
    } catch (const std::exception& e) {
        return fmt::format("{} cannot hold a {}x{} frame with {} samples a pixel ({}); give a "
                           "smaller render.size",
                           renderer, width, height, samples, e.what());
    }
    return {};
}

std::unique_ptr<GlContext> make_gl_context(std::string_view backend) {
    if (backend == "auto")
        return make_gl_context(std::optional<GlBackend>());
    if (const auto named = choice_named<GlBackend>(backend))
        return make_gl_context(named);
    throw std::invalid_argument("unknown GL backend: " + std::string(backend));
}

std::unique_ptr<GlContext> make_gl_context(std::optional<GlBackend> backend) {
    if (backend == GlBackend::egl)
        return make_egl_context();
    if (backend == GlBackend::osmesa)
        return make_osmesa_context();
    // auto: EGL first (it reaches GPUs), then OSMesa (always software).
    std::string tried;
    try {
        return make_egl_context();
    } catch (const GlContextError& e) {
        tried = e.what();
    }
    try {
        return make_osmesa_context();
    } catch (const GlContextError& e) {
        throw GlContextError("no OpenGL 4.5 context could be made; tried\n  " + tried + "\n  " +
                             e.what());
    }
}

} // namespace sph
