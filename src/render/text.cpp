#include "render/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <embedded_shaders.hpp>
#include <fmt/format.h>
#include <fstream>
#include <ft2build.h>
#include FT_FREETYPE_H
#include <glm/gtc/type_ptr.hpp>

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

constexpr char first_char = ' ';
constexpr int char_count = 95; // ' ' .. '~'

bool readable(const std::string& path) {
    return !path.empty() && std::ifstream(path, std::ios::binary).good();
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

TextFace::TextFace(const std::string& font_file, int pixel_size, std::string& warning) {
    if (!font_file.empty())
        load_font(font_file, pixel_size, warning);
    if (!face_)
        make_bitmap_font(pixel_size);
}

TextFace::~TextFace() {
    if (face_)
        FT_Done_Face(static_cast<FT_Face>(face_));
    if (library_)
        FT_Done_FreeType(static_cast<FT_Library>(library_));
}

void TextFace::load_font(const std::string& file, int pixel_size, std::string& warning) {
    FT_Library library = nullptr;
    FT_Face face = nullptr;
    if (FT_Init_FreeType(&library) != 0) {
        warning = "FreeType did not start; the overlay's text is drawn in the bitmap font";
        return;
    }
    library_ = library;
    if (FT_New_Face(library, file.c_str(), 0, &face) != 0 ||
        FT_Set_Pixel_Sizes(face, 0, FT_UInt(pixel_size)) != 0) {
        if (face)
            FT_Done_Face(face);
        warning = fmt::format("FreeType cannot read the font {}; the overlay's text is drawn in "
                              "the bitmap font",
                              file);
        return;
    }
    face_ = face;
    kerning_ = FT_HAS_KERNING(face);
    ascent_ = float(face->size->metrics.ascender) / 64.f;
    descent_ = -float(face->size->metrics.descender) / 64.f;
    AtlasPacker atlas(512);
    std::vector<std::pair<int, int>> at(char_count);
    // Rendered with the light hinting (vertical only): shapes keep their
    // design widths, stems sit on whole pixels.
    for (int c = 0; c < char_count; ++c) {
        if (FT_Load_Char(face, FT_ULong(first_char + c), FT_LOAD_RENDER | FT_LOAD_TARGET_LIGHT) !=
            0)
            continue;
        const FT_GlyphSlot slot = face->glyph;
        const FT_Bitmap& bitmap = slot->bitmap;
        Glyph& g = glyphs_[std::size_t(c)];
        g.left = slot->bitmap_left;
        g.top = slot->bitmap_top;
        g.width = int(bitmap.width);
        g.height = int(bitmap.rows);
        g.advance = float(slot->advance.x) / 64.f;
        at[std::size_t(c)] = atlas.place(g.width, g.height);
        for (int row = 0; row < g.height; ++row)
            for (int col = 0; col < g.width; ++col)
                atlas.texels[std::size_t(at[std::size_t(c)].second + row) * 512 +
                             std::size_t(at[std::size_t(c)].first + col)] =
                    bitmap.buffer[std::ptrdiff_t(row) * bitmap.pitch + col];
        if (first_char + c == 'H')
            cap_height_ = float(g.top);
    }
    const float w = 512, h = float(atlas.height());
    for (int c = 0; c < char_count; ++c) {
        Glyph& g = glyphs_[std::size_t(c)];
        g.u0 = float(at[std::size_t(c)].first) / w;
        g.v0 = float(at[std::size_t(c)].second) / h;
        g.u1 = float(at[std::size_t(c)].first + g.width) / w;
        g.v1 = float(at[std::size_t(c)].second + g.height) / h;
    }
    atlas_ = gl::Texture::generate();
    glBindTexture(GL_TEXTURE_2D, atlas_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, 512, atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                 atlas.texels.data());
    // Texel for pixel: quads on whole pixels, sampled at texel centres.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void TextFace::make_bitmap_font(int pixel_size) {
    // stb_easy_font's capitals are 7 glyph pixels tall in a 10-pixel line;
    // whole pixels per glyph pixel keep its edges sharp.
    const int scale = std::max(1, int(std::lround(0.7 * pixel_size / 7.0)));
    bitmap_scale_ = float(scale);
    cap_height_ = 7.f * float(scale);
    ascent_ = 8.f * float(scale);
    descent_ = 3.f * float(scale);
    AtlasPacker atlas(512);
    std::vector<std::pair<int, int>> at(char_count);
    std::vector<char> buffer(64 * 1024);
    for (int c = 0; c < char_count; ++c) {
        char text[2] = {char(first_char + c), 0};
        const int quads =
            stb_easy_font_print(0, 0, text, nullptr, buffer.data(), int(buffer.size()));
        Glyph& g = glyphs_[std::size_t(c)];
        g.advance = float(stb_easy_font_width(text) * scale);
        g.width = std::max(1, int(g.advance));
        g.height = 10 * scale;
        g.left = 0;
        g.top = int(cap_height_);
        at[std::size_t(c)] = atlas.place(g.width, g.height);
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
                        atlas.texels[std::size_t(at[std::size_t(c)].second + y) * 512 +
                                     std::size_t(at[std::size_t(c)].first + x)] = 255;
        }
    }
    const float w = 512, h = float(atlas.height());
    for (int c = 0; c < char_count; ++c) {
        Glyph& g = glyphs_[std::size_t(c)];
        g.u0 = float(at[std::size_t(c)].first) / w;
        g.v0 = float(at[std::size_t(c)].second) / h;
        g.u1 = float(at[std::size_t(c)].first + g.width) / w;
        g.v1 = float(at[std::size_t(c)].second + g.height) / h;
    }
    atlas_ = gl::Texture::generate();
    glBindTexture(GL_TEXTURE_2D, atlas_.id());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, 512, atlas.height(), 0, GL_RED, GL_UNSIGNED_BYTE,
                 atlas.texels.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
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
    for (const char ch : text) {
        const int c = static_cast<unsigned char>(ch) - first_char;
        if (c < 0 || c >= char_count)
            continue;
        const Glyph& g = glyphs_[std::size_t(c)];
        if (kerning_ && previous) {
            auto* face = static_cast<FT_Face>(face_);
            FT_Vector kern;
            if (FT_Get_Kerning(face, previous, FT_Get_Char_Index(face, FT_ULong(ch)),
                               FT_KERNING_DEFAULT, &kern) == 0)
                pen += float(kern.x) / 64.f;
        }
        if (face_)
            previous = FT_Get_Char_Index(static_cast<FT_Face>(face_), FT_ULong(ch));
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
