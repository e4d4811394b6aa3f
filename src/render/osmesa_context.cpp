// OSMesa: Mesa's off-screen software rasteriser (llvmpipe), available where no
// EGL is. It wants a client-memory colour buffer to make the context current;
// a small one does, since sphclip draws into framebuffer objects.
#include "platform/shared_library.hpp"
#include "render/gl_context.hpp"

#include <GL/osmesa.h>
#include <vector>

namespace sph {

namespace {

// OSMesa's functions, from its library (with LLVM behind it) loaded when the
// first context is made (platform/shared_library.hpp says why not at start).
// SPHCLIP_OSMESA_SONAME: the library's soname, from CMake.
struct OsmesaFunctions {
    decltype(&OSMesaCreateContextAttribs) create_context;
    decltype(&OSMesaMakeCurrent) make_current;
    decltype(&OSMesaDestroyContext) destroy_context;
    decltype(&OSMesaGetProcAddress) get_proc_address;
};

const OsmesaFunctions& osmesa() {
    static const OsmesaFunctions loaded = [] {
        try {
            const std::string soname = SPHCLIP_OSMESA_SONAME;
            return OsmesaFunctions{
                library_function<decltype(&OSMesaCreateContextAttribs)>(
                    soname, "OSMesaCreateContextAttribs"),
                library_function<decltype(&OSMesaMakeCurrent)>(soname, "OSMesaMakeCurrent"),
                library_function<decltype(&OSMesaDestroyContext)>(soname, "OSMesaDestroyContext"),
                library_function<decltype(&OSMesaGetProcAddress)>(soname, "OSMesaGetProcAddress")};
        } catch (const std::runtime_error& error) {
            throw GlContextError(std::string("OSMesa: ") + error.what());
        }
    }();
    return loaded;
}

void* osmesa_proc(const char* name) {
    return reinterpret_cast<void*>(osmesa().get_proc_address(name));
}

class OsmesaContext final : public GlContext {
  public:
    OsmesaContext() {
        const int attributes[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  24,
                                  OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  4,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  5,
                                  0};
        context_ = osmesa().create_context(attributes, nullptr);
        if (!context_)
            throw GlContextError("OSMesa: OSMesaCreateContextAttribs for OpenGL 4.5 core failed");
        if (!osmesa().make_current(context_, buffer_.data(), GL_UNSIGNED_BYTE, side, side)) {
            osmesa().destroy_context(context_);
            throw GlContextError("OSMesa: OSMesaMakeCurrent failed");
        }
        try {
            load_functions(osmesa_proc, "osmesa");
        } catch (...) {
            osmesa().destroy_context(context_);
            throw;
        }
    }
    ~OsmesaContext() override { osmesa().destroy_context(context_); }

  private:
    static constexpr int side = 16;
    std::vector<unsigned char> buffer_ = std::vector<unsigned char>(side * side * 4);
    OSMesaContext context_ = nullptr;
};

} // namespace

std::unique_ptr<GlContext> make_osmesa_context() {
    return std::make_unique<OsmesaContext>();
}

} // namespace sph
