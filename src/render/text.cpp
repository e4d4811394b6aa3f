#include "render/text.hpp"

#include "output/files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <embedded_shaders.hpp>
#include <fmt/format.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <glm/gtc/type_ptr.hpp>
#include <sys/stat.h>
#include <unistd.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#include <stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace sph {

namespace {

constexpr char32_t first_char = U' ', last_ascii = U'~';

// What every atlas holds: printable ASCII, Latin-1 (accents, degree, micro,
// superscripts), Greek (rho, mu, Delta in labels), and a few symbols
// (minus, en and em dashes, ellipsis, arrows, approximately, <=, >=), then
// every other character of `texts`.
std::vector<char32_t> atlas_characters(const std::vector<std::string>& texts) {
    std::vector<char32_t> set;
    for (char32_t c = first_char; c <= last_ascii; ++c)
        set.push_back(c);
    for (char32_t c = 0xa1; c <= 0xff; ++c)
        set.push_back(c);
    for (char32_t c = 0x391; c <= 0x3c9; ++c)
        set.push_back(c);
    for (const char32_t c :
         {0x2013, 0x2014, 0x2026, 0x2190, 0x2192, 0x2212, 0x2248, 0x2264, 0x2265})
        set.push_back(c);
    for (const std::string& text : texts)
        for (std::size_t at = 0; at < text.size();)
            if (const char32_t c = next_character(text, at); c >= first_char)
                set.push_back(c);
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
    return set;
}

// A regular file we may read, by stat alone: opening a FIFO would block.
bool readable(const std::string& path) {
    struct stat info {};
    return !path.empty() && ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
           std::uint64_t(info.st_size) <= font_file_limit.bytes &&
           ::access(path.c_str(), R_OK) == 0;
}

// The face of `bytes` at `pixel_size`, or null.
FT_Face open_face(FT_Library library, const std::string& bytes, int pixel_size) {
    FT_Face face = nullptr;
    if (FT_New_Memory_Face(library, reinterpret_cast<const FT_Byte*>(bytes.data()),
                           FT_Long(bytes.size()), 0, &face) != 0)
        return nullptr;
    if (FT_Set_Pixel_Sizes(face, 0, FT_UInt(pixel_size)) != 0) {
        FT_Done_Face(face);
        return nullptr;
    }
    return face;
}

// fontconfig's choice for `pattern`, or empty (no fc-match, or no match).
std::string fc_match(const char* pattern) {
    const std::string command = fmt::format("fc-match -f '%{{file}}' '{}' 2>/dev/null", pattern);
    std::FILE* pipe = popen(command.c_str(), "r");
    if (!pipe)
        return {};
    std::string out;
    char buffer[512];
    while (const std::size_t n = std::fread(buffer, 1, sizeof buffer, pipe))
        out.append(buffer, n);
    pclose(pipe);
    return out;
}

// Glyph bitmaps packed left to right in rows of an atlas `width` texels wide.
struct AtlasPacker {
    int width, x = 0, y = 0, row_height = 0;
    std::vector<std::uint8_t> texels;
    explicit AtlasPacker(int w) : width(w) {}
    // The top-left texel where a w x h bitmap goes, growing the atlas.
    std::pair<int, int> place(int w, int h) {
        if (x + w + 1 > width) {
            x = 0;
            y += row_height + 1;
            row_height = 0;
        }
        const std::pair<int, int> at{x, y};
        x += w + 1; // a texel of space: no bleeding between glyphs
        row_height = std::max(row_height, h);
        texels.resize(std::size_t(width) * std::size_t(y + row_height + 1), 0);
        return at;
    }
    int height() const { return y + row_height + 1; }
};

} // namespace

char32_t next_character(std::string_view text, std::size_t& at) {
    const auto byte = [&](std::size_t k) {
        return static_cast<unsigned char>(text[k]);
    };
    const unsigned lead = byte(at);
    const int length = lead < 0x80       ? 1
                       : lead >> 5 == 6  ? 2
                       : lead >> 4 == 14 ? 3
                       : lead >> 3 == 30 ? 4
                                         : 0;
    if (length == 1) {
        ++at;
        return lead;
    }
    char32_t c = length == 2 ? lead & 0x1f : length == 3 ? lead & 0x0f : lead & 0x07;
    bool ok = length > 0 && at + std::size_t(length) <= text.size();
    for (int k = 1; ok && k < length; ++k) {
        ok = (byte(at + std::size_t(k)) & 0xc0) == 0x80;
        c = (c << 6) | (byte(at + std::size_t(k)) & 0x3f);
    }
    // Overlong forms, surrogates and values past U+10FFFF are malformed too.
    static constexpr char32_t least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (!ok || c < least[length] || (c >= 0xd800 && c <= 0xdfff) || c > 0x10ffff) {
        ++at;
        return 0xfffd;
    }
    at += std::size_t(length);
    return c;
}

const std::vector<std::string>& default_font_paths() {
    static const std::vector<std::string> paths{
        "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",   // Debian, Ubuntu: fonts-dejavu-core
        "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf", // Fedora
        "/usr/share/fonts/TTF/DejaVuSans.ttf",               // Arch
        "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    };
    return paths;
}

std::string find_font(const std::string& requested, std::string& warning) {
    warning.clear();
    if (!requested.empty()) {
        if (readable(requested))
            return requested;
        warning = fmt::format("render.font: cannot read {}; using the default font", requested);
    }
    for (const std::string& path : default_font_paths())
        if (readable(path))
            return path;
    if (std::string path = fc_match("DejaVu Sans"); readable(path))
        return path;
    warning = fmt::format("{}no font found (looked for {} and asked fc-match); the overlay's "
                          "text is drawn in the bitmap font (install fonts-dejavu-core, or set "
                          "render.font)",
                          warning.empty() ? "" : warning + "; ", default_font_paths()[0]);
    return {};
}

std::string font_problem(const std::string& font_file) {
    std::string bytes;
    try {
        bytes = read_input_file(font_file, font_file_limit);
    } catch (const FileReadError& e) {
        return fmt::format("cannot read the font {}: {}", font_file, e.reason);
    }
    FT_Library library = nullptr;
    if (FT_Init_FreeType(&library) != 0)
        return "FreeType did not start";
    FT_Face face = open_face(library, bytes, 16);
    const bool ok = face != nullptr;
    if (face)
        FT_Done_Face(face);
    FT_Done_FreeType(library);
    return ok ? std::string()
              : fmt::format("{} is not a font FreeType can read (TrueType, OpenType, Type 1...)",
                            font_file);
}

TextFace::TextFace(const std::string& font_file, int pixel_size, std::string& warning,
                   const std::vector<std::string>& texts) {
    if (!font_file.empty() && load_font(font_file, pixel_size, warning, atlas_characters(texts)))
        return;
    make_bitmap_font(pixel_size);
}

TextFace::~TextFace() {
    if (face_)
        FT_Done_Face(static_cast<FT_Face>(face_));
    if (library_)
        FT_Done_FreeType(static_cast<FT_Library>(library_));
}

bool TextFace::load_font(const std::string& file, int pixel_size, std::string& warning,
                         const std::vector<char32_t>& characters) {
    FT_Library library = nullptr;
    if (FT_Init_FreeType(&library) != 0) {
        warning = "FreeType did not start; the overlay's text is drawn in the bitmap font";
        return false;
    }
    library_ = library;
    try {
        font_bytes_ = read_input_file(file, font_file_limit);
    } catch (const FileReadError& e) {
        warning = fmt::format("cannot read the font {}: {}; the overlay's text is drawn in the "
                              "bitmap font",
                              file, e.reason);
        return false;
    }
    FT_Face face = open_face(library, font_bytes_, pixel_size);
    if (!face) {
        warning = fmt::format("FreeType cannot read the font {}; the overlay's text is drawn in "
                              "the bitmap font",
                              file);
        return false;
    }
    face_ = face;
    kerning_ = FT_HAS_KERNING(face);
    ascent_ = float(face->size->metrics.ascender) / 64.f;
    descent_ = -float(face->size->metrics.descender) / 64.f;
    std::vector<char32_t> held;
    std::vector<GlyphImage> images;
    // Rendered with the light hinting (vertical only): shapes keep their
    // design widths, stems sit on whole pixels. A character the font lacks
    // is left out, and shows as '?'.
    for (const char32_t c : characters) {
        if (c != '?' && FT_Get_Char_Index(face, FT_ULong(c)) == 0)
            continue;
        if (FT_Load_Char(face, FT_ULong(c), FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT) != 0)
            continue;
        const FT_GlyphSlot slot = face->glyph;
        const FT_Bitmap& bitmap = slot->bitmap;
        GlyphImage image;
        Glyph& g = image.glyph;
        g.left = slot->bitmap_left;
        g.top = slot->bitmap_top;
        g.width = int(bitmap.width);
        g.height = int(bitmap.rows);
        g.advance = float(slot->advance.x) / 64.f;
        image.coverage.resize(std::size_t(g.width) * std::size_t(g.height));
        for (int row = 0; row < g.height; ++row)
            for (int col = 0; col < g.width; ++col)
                image.coverage[std::size_t(row) * std::size_t(g.width) + std::size_t(col)] =
                    bitmap.buffer[std::ptrdiff_t(row) * bitmap.pitch + col];
        if (c == 'H')
            cap_height_ = float(g.top);
        held.push_back(c);
        images.push_back(std::move(image));
    }
    build_atlas(std::move(held), std::move(images));
    return true;
}

void TextFace::make_bitmap_font(int pixel_size) {
    // stb_easy_font's capitals are 7 glyph pixels tall in a 10-pixel line;
    // whole pixels per glyph pixel keep its edges sharp.
    const int scale = std::max(1, int(std::lround(0.7 * pixel_size / 7.0)));
    bitmap_scale_ = float(scale);
    cap_height_ = 7.f * float(scale);
    ascent_ = 8.f * float(scale);
    descent_ = 3.f * float(scale);
    std::vector<char32_t> held;
    std::vector<GlyphImage> images;
    std::vector<char> buffer(64 * 1024);
    // stb_easy_font has printable ASCII only.
    for (char32_t c = first_char; c <= last_ascii; ++c) {
        char text[2] = {char(c), 0};
        const int quads =
            stb_easy_font_print(0, 0, text, nullptr, buffer.data(), int(buffer.size()));
        GlyphImage image;
        Glyph& g = image.glyph;
        g.advance = float(stb_easy_font_width(text) * scale);
        g.width = std::max(1, int(g.advance));
        g.height = 10 * scale;
        g.left = 0;
        g.top = int(cap_height_);
        image.coverage.assign(std::size_t(g.width) * std::size_t(g.height), 0);
        const auto* v = reinterpret_cast<const float*>(buffer.data());
        for (int q = 0; q < quads; ++q) {
            // A quad's corners 0 and 2 are opposite (16 bytes a vertex).
            const float* a = v + q * 16;
            const float* b = v + q * 16 + 8;
            for (int y = int(std::min(a[1], b[1])) * scale; y < int(std::max(a[1], b[1])) * scale;
                 ++y)
                for (int x = int(std::min(a[0], b[0])) * scale;
                     x < int(std::max(a[0], b[0])) * scale; ++x)
                    if (x >= 0 && x < g.width && y >= 0 && y < g.height)
                        image.coverage[std::size_t(y) * std::size_t(g.width) + std::size_t(x)] =
                            255;
        }
        held.push_back(c);
        images.push_back(std::move(image));
    }
    build_atlas(std::move(held), std::move(images));
}

void TextFace::build_atlas(std::vector<char32_t> characters, std::vector<GlyphImage> images) {
    // 512 texels, or wider for glyphs wider than that (frames thousands of
    // pixels tall).
    int width = 512;
    for (const GlyphImage& image : images)
        width = std::max(width, image.glyph.width + 1);
    AtlasPacker atlas(width);
    std::vector<std::pair<int, int>> at(images.size());
    for (std::size_t k = 0; k < images.size(); ++k) {
        const Glyph& g = images[k].glyph;
        at[k] = atlas.place(g.width, g.height);
        for (int row = 0; row < g.height; ++row)
            std::copy_n(images[k].coverage.begin() + std::ptrdiff_t(row) * g.width, g.width,
                        atlas.texels.begin() + std::ptrdiff_t(at[k].second + row) * width +
                            at[k].first);
    }
    const float w = float(width), h = float(atlas.height());
    glyphs_.clear();
    for (std::size_t k = 0; k < images.size(); ++k) {
        Glyph g = images[k].glyph;
        g.u0 = float(at[k].first) / w;
        g.v0 = float(at[k].second) / h;
        g.u1 = float(at[k].first + g.width) / w;
        g.v1 = float(at[k].second + g.height) / h;
        glyphs_.push_back(g);
    }
    characters_ = std::move(characters);
    atlas_ = gl::Texture::generate();
    glBindTexture(GL_TEXTURE_2D, atlas_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, width, atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                 atlas.texels.data());
    // Texel for pixel: quads on whole pixels, sampled at texel centres.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

const TextFace::Glyph& TextFace::glyph(char32_t c) const {
    auto found = std::lower_bound(characters_.begin(), characters_.end(), c);
    if (found == characters_.end() || *found != c)
        found = std::lower_bound(characters_.begin(), characters_.end(), U'?');
    return glyphs_[std::size_t(found - characters_.begin())];
}

float TextFace::width(std::string_view text) const {
    std::vector<TextVertex> quads;
    append(text, 0, 0, quads);
    float right = 0;
    for (const TextVertex& v : quads)
        right = std::max(right, v.x);
    return right;
}

void TextFace::append(std::string_view text, float x, float baseline,
                      std::vector<TextVertex>& out) const {
    float pen = std::round(x);
    const float base = std::round(baseline);
    unsigned previous = 0;
    for (std::size_t at = 0; at < text.size();) {
        const char32_t ch = next_character(text, at);
        if (ch < first_char)
            continue;
        const Glyph& g = glyph(ch);
        if (face_) {
            auto* face = static_cast<FT_Face>(face_);
            const unsigned index = FT_Get_Char_Index(face, FT_ULong(ch));
            FT_Vector kern;
            if (kerning_ && previous && index &&
                FT_Get_Kerning(face, previous, index, FT_KERNING_DEFAULT, &kern) == 0)
                pen += float(kern.x) / 64.f;
            previous = index;
        }
        if (g.width > 0 && g.height > 0) {
            const float x0 = std::round(pen) + float(g.left), y0 = base - float(g.top);
            const float x1 = x0 + float(g.width), y1 = y0 + float(g.height);
            const TextVertex a{x0, y0, g.u0, g.v0}, b{x1, y0, g.u1, g.v0}, c1{x1, y1, g.u1, g.v1},
                d{x0, y1, g.u0, g.v1};
            for (const TextVertex& v : {a, b, c1, a, c1, d})
                out.push_back(v);
        }
        pen += g.advance;
    }
}

TextPainter::TextPainter()
    : program_(gl::link_program(shaders::text_vert, shaders::text_frag, "")),
      vao_(gl::VertexArray::generate()), buffer_(gl::Buffer::generate()) {
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.id());
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(TextVertex), nullptr);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(TextVertex), reinterpret_cast<void*>(8));
    glBindVertexArray(0);
    // The atlas on unit 1: unit 0 holds the colour map.
    glProgramUniform1i(program_.id(), glGetUniformLocation(program_.id(), "u_atlas"), 1);
}

void TextPainter::draw(const std::vector<TextVertex>& vertices, const TextFace& face,
                       const glm::mat4& transform, const glm::vec4& colour) const {
    if (vertices.empty())
        return;
    glUseProgram(program_.id());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, face.atlas().id());
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(vao_.id());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.id());
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size() * sizeof(TextVertex)), vertices.data(),
                 GL_STREAM_DRAW);
    glUniformMatrix4fv(glGetUniformLocation(program_.id(), "u_transform"), 1, GL_FALSE,
                       glm::value_ptr(transform));
    glUniform4fv(glGetUniformLocation(program_.id(), "u_colour"), 1, glm::value_ptr(colour));
    glEnable(GL_BLEND);
    // Colour only: the frame stays opaque (a PNG with see-through edges
    // would show whatever a viewer puts behind it).
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    glDrawArrays(GL_TRIANGLES, 0, GLsizei(vertices.size()));
    glDisable(GL_BLEND);
}

} // namespace sph
