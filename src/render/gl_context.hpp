#pragma once
// A headless OpenGL 4.5 core context, from EGL (no display: Mesa's surfaceless
// platform or an EGL device such as NVIDIA's) or from OSMesa. Rendering goes to
// framebuffer objects, so no window system surface is ever needed. One
// context per process at a time: creating it loads the GL functions.

#include "scene/render_choices.hpp"

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

struct GlInfo {
    std::string backend; // "egl" or "osmesa"
    std::string vendor, renderer, version;
    // What bounds a frame: its width and height, and its multisampling.
    int max_renderbuffer_size = 0, max_viewport_width = 0, max_viewport_height = 0, max_samples = 0;
};

// No context could be made; the message lists every attempt.
struct GlContextError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

class GlContext {
  public:
    virtual ~GlContext() = default;
    const GlInfo& info() const { return info_; }

  protected:
    // Loads the GL functions through `get_proc` and reads vendor and version;
    // throws GlContextError when the context is not GL 4.5 core capable.
    void load_functions(void* (*get_proc)(const char*), std::string backend);

  private:
    GlInfo info_;
};

// Why the context cannot draw a width x height frame with `samples`
// samples (its limits, or a framebuffer it cannot complete, e.g. for want of
// memory); empty when it can. Allocates the frame's buffers once and frees
// them, so that a run learns it before it writes anything.
std::string frame_size_problem(const GlContext& context, int width, int height, int samples);

// The backend's context; none (auto): EGL first, then OSMesa.
std::unique_ptr<GlContext> make_gl_context(std::optional<GlBackend> backend);
// The same by name: "egl", "osmesa" or "auto" (for command-line flags and
// the tests' lists); throws std::invalid_argument for another name.
std::unique_ptr<GlContext> make_gl_context(std::string_view backend);

// Each backend's factory; throws GlContextError saying what failed.
std::unique_ptr<GlContext> make_egl_context();
std::unique_ptr<GlContext> make_osmesa_context();

} // namespace sph
