// EGL without a display: Mesa's surfaceless platform (llvmpipe or a Mesa GPU
// driver), else the first EGL device (how NVIDIA's driver offers headless
// contexts), else the default display.
#include "render/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <cstdio>
#include <cstring>

namespace sph {

namespace {

bool has_extension(const char* list, const char* name) {
    if (!list)
        return false;
    const std::size_t length = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length)
        if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0'))
            return true;
    return false;
}

void* egl_proc(const char* name) {
    return reinterpret_cast<void*>(eglGetProcAddress(name));
}

class EglContext final : public GlContext {
  public:
    EglContext() {
        display_ = open_display();
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display_, &major, &minor))
            fail("eglInitialize failed");
        if (!eglBindAPI(EGL_OPENGL_API))
            fail("the EGL display offers no desktop OpenGL");
        // Surface type 0: any config, since nothing is drawn to an EGL surface
        // (the default would ask for window support, which surfaceless lacks).
        const EGLint config_attributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                            0, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (!eglChooseConfig(display_, config_attributes, &config, 1, &count) || count == 0)
            fail("no EGL config renders OpenGL");
        const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             4,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             5,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_NONE};
        context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attributes);
        if (context_ == EGL_NO_CONTEXT)
            fail("eglCreateContext for OpenGL 4.5 core failed");
        // No surface: everything is drawn into framebuffer objects.
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            fail("eglMakeCurrent without a surface failed");
        load_functions(egl_proc, "egl");
    }
    ~EglContext() override { release(); }

  private:
    static EGLDisplay open_display() {
        const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
        auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
            eglGetProcAddress("eglGetPlatformDisplayEXT"));
        if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
            EGLDisplay d =
                get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
            if (d != EGL_NO_DISPLAY)
                return d;
        }
        auto query_devices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        if (get_platform_display && query_devices &&
            has_extension(client, "EGL_EXT_platform_device")) {
            EGLDeviceEXT devices[8];
            EGLint count = 0;
            if (query_devices(8, devices, &count) && count > 0) {
                EGLDisplay d = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
                if (d != EGL_NO_DISPLAY)
                    return d;
            }
        }
        return eglGetDisplay(EGL_DEFAULT_DISPLAY);
    }

    [[noreturn]] void fail(const std::string& what) {
        const EGLint code = eglGetError();
        release();
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04x", code);
        throw GlContextError("EGL: " + what + " (EGL error " + hex + ")");
    }

    void release() {
        if (display_ == EGL_NO_DISPLAY)
            return;
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (context_ != EGL_NO_CONTEXT)
            eglDestroyContext(display_, context_);
        eglTerminate(display_);
        display_ = EGL_NO_DISPLAY;
        context_ = EGL_NO_CONTEXT;
    }

    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

} // namespace

std::unique_ptr<GlContext> make_egl_context() {
    return std::make_unique<EglContext>();
}

} // namespace sph
