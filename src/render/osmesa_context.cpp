// OSMesa: Mesa's off-screen software rasteriser (llvmpipe), available where no
// EGL is. It wants a client-memory colour buffer to make the context current;
// a small one does, since sphclip draws into framebuffer objects.
#include "render/gl_context.hpp"

#include <GL/osmesa.h>
#include <vector>

namespace sph {

namespace {

void* osmesa_proc(const char* name) {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
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
        context_ = OSMesaCreateContextAttribs(attributes, nullptr);
        if (!context_)
            throw GlContextError("OSMesa: OSMesaCreateContextAttribs for OpenGL 4.5 core failed");
        if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, side, side)) {
            OSMesaDestroyContext(context_);
            throw GlContextError("OSMesa: OSMesaMakeCurrent failed");
        }
        try {
            load_functions(osmesa_proc, "osmesa");
        } catch (...) {
            OSMesaDestroyContext(context_);
            throw;
        }
    }
    ~OsmesaContext() override { OSMesaDestroyContext(context_); }

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
