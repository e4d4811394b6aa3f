#include "render/gl_context.hpp"

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
}

std::unique_ptr<GlContext> make_gl_context(std::string_view backend) {
    if (backend == "egl")
        return make_egl_context();
    if (backend == "osmesa")
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
