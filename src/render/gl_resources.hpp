#pragma once
// The renderer's GL objects and their lifetime: owning handles that delete
// their object when they go (the context must still be current then, as it
// is while a FrameRenderer lives), the shader compile and link helpers, the
// colour map as a texture, and the frame's render target.

#include "output/image.hpp"
#include "scene/render_choices.hpp"

#include <glad/gl.h>
#include <string>
#include <string_view>
#include <utility>

namespace sph::gl {

enum class Kind { program, buffer, vertex_array, texture, renderbuffer, framebuffer };
GLuint generate_object(Kind kind);
void delete_object(Kind kind, GLuint id); // 0: nothing

// One GL object of kind K, owned: moved, never copied; 0 is no object.
template <Kind K>
class Object {
  public:
    Object() = default;
    // A new, empty object (glGen* / glCreateProgram).
    static Object generate() { return Object(generate_object(K)); }
    // Takes ownership of `id`.
    explicit Object(GLuint id) : id_(id) {}
    ~Object() { delete_object(K, id_); }
    Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
    Object& operator=(Object&& other) noexcept {
        if (this != &other) {
            delete_object(K, id_);
            id_ = std::exchange(other.id_, 0);
        }
        return *this;
    }
    Object(const Object&) = delete;
    Object& operator=(const Object&) = delete;

    GLuint id() const { return id_; }
    explicit operator bool() const { return id_ != 0; }

  private:
    GLuint id_ = 0;
};

using Program = Object<Kind::program>;
using Buffer = Object<Kind::buffer>;
using VertexArray = Object<Kind::vertex_array>;
using Texture = Object<Kind::texture>;
using Renderbuffer = Object<Kind::renderbuffer>;
using Framebuffer = Object<Kind::framebuffer>;

// A program from a vertex and a fragment shader, each compiled as
// "#version 450 core", then `common` (defines, shared functions), then its
// own text. Throws std::runtime_error with the compiler's or linker's log.
Program link_program(std::string_view vertex, std::string_view fragment, std::string_view common);

// Throws std::runtime_error naming `where` if GL has recorded an error.
void check_gl(const char* where);

// The colour map (colour_maps.hpp) as a 256-texel 1D texture, linearly
// interpolated and clamped at its ends.
Texture make_colour_map_texture(ColourMap map);
// Binds it to texture unit 0, where the sphere and overlay programs read it.
void bind_colour_map(const Texture& texture);

// The frame's background (linear RGB), behind the scene and the overlay.
inline constexpr float background[3] = {0.08f, 0.09f, 0.11f};

// Where a frame is drawn: multisampled colour and depth, resolved into a
// plain colour buffer to be read back.
class RenderTarget {
  public:
    RenderTarget(int width, int height, int samples);
    // Binds the multisampled buffer, clears it to the background, and turns
    // on the depth test (less) and multisampling.
    void begin();
    // Resolves the samples and reads the pixels back, rows top-down.
    Image read() const;
    // The multisampled framebuffer (the passes that read its depth).
    GLuint framebuffer() const { return msaa_.id(); }

  private:
    int width_, height_;
    Renderbuffer msaa_colour_, msaa_depth_, resolve_colour_;
    Framebuffer msaa_, resolve_;
};

} // namespace sph::gl
