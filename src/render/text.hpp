#pragma once
// Text for the overlay: a real font rasterised by FreeType once, at one
// pixel size, into an atlas texture of anti-aliased glyphs (printable
// ASCII, Latin-1, Greek, a few symbols, and every other character of the
// texts it is made for; text is UTF-8), drawn as one textured quad per glyph on whole pixels so the
// coverage FreeType computed reaches the image unchanged. Without a font
// file the stb_easy_font bitmap glyphs stand in (solid quads), with a
// warning: a run never fails for want of a font.

#include "render/fonts.hpp"
#include "render/gl_resources.hpp"

#include <array>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

// A vertex of a glyph quad: pixels (origin top left, y down) and atlas
// texture coordinates.
struct TextVertex {
    float x, y, u, v;
};

// The next character of UTF-8 `text` at byte `at`, moving `at` past it; a
// malformed sequence is one U+FFFD for its first byte.
char32_t next_character(std::string_view text, std::size_t& at);

class TextFace {
  public:
    // `pixel_size`: the em height in px. `font_file` empty or unreadable by
    // FreeType: the bitmap font at about that size (and `warning` says why);
    // it has ASCII only, and other characters show as '?'. `texts`: the
    // UTF-8 texts to be drawn, whose characters the atlas must hold beyond
    // its fixed set.
    TextFace(const std::string& font_file, int pixel_size, std::string& warning,
             const std::vector<std::string>& texts = {});
    ~TextFace();
    TextFace(const TextFace&) = delete;
    TextFace& operator=(const TextFace&) = delete;

    bool from_font() const { return face_ != nullptr; }
    // Pixels: the advance width of `text`, the height of a capital above the
    // baseline, and the line's extent above and below it.
    float width(std::string_view text) const;
    float cap_height() const { return cap_height_; }
    float ascent() const { return ascent_; }
    float descent() const { return descent_; }
    // Appends two triangles per glyph for `text`, its baseline starting at
    // (x, baseline), snapped to whole pixels.
    void append(std::string_view text, float x, float baseline, std::vector<TextVertex>& out) const;
    // The glyph atlas (one channel: coverage), to bind while drawing.
    const gl::Texture& atlas() const { return atlas_; }

  private:
    struct Glyph {
        int left = 0, top = 0, width = 0, height = 0; // px, from the pen on the baseline
        float advance = 0;                            // px
        float u0 = 0, v0 = 0, u1 = 0, v1 = 0;         // in the atlas
    };
    // A glyph's metrics and coverage (rows top-down, width x height bytes).
    struct GlyphImage {
        Glyph glyph;
        std::vector<std::uint8_t> coverage;
    };
    bool load_font(const std::string& file, int pixel_size, std::string& warning,
                   const std::vector<char32_t>& characters);
    void make_bitmap_font(int pixel_size);
    // Packs the glyphs into the atlas texture; characters_[k] has glyphs_[k].
    void build_atlas(std::vector<char32_t> characters, std::vector<GlyphImage> images);
    // The glyph for `c`; '?' for one the atlas lacks.
    const Glyph& glyph(char32_t c) const;

    std::string font_bytes_;  // the font file, read once: FreeType reads the face from here
    void* library_ = nullptr; // FT_Library
    void* face_ = nullptr;    // FT_Face: kept for kerning
    bool kerning_ = false;
    std::vector<char32_t> characters_; // sorted
    std::vector<Glyph> glyphs_;        // of characters_
    float bitmap_scale_ = 1;           // bitmap font: px per glyph pixel
    float cap_height_ = 0, ascent_ = 0, descent_ = 0;
    gl::Texture atlas_;
};

// Draws glyph quads in one colour, blended over the image.
class TextPainter {
  public:
    TextPainter();
    void draw(const std::vector<TextVertex>& vertices, const TextFace& face,
              const glm::mat4& transform, const glm::vec4& colour) const;

  private:
    gl::Program program_;
    gl::VertexArray vao_;
    gl::Buffer buffer_;
};

} // namespace sph
