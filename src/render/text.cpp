#include "render/text.hpp"

#include <algorithm>
#include <string>

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

void append_text_triangles(std::string_view text, float x, float y, float scale,
                           std::vector<float>& xy) {
    // stb_easy_font writes 4 vertices of 16 bytes (x, y, z, colour) per quad.
    std::string copy(text);
    // stb_easy_font needs about 270 bytes per character on average, more for
    // some glyphs: leave ample room.
    std::vector<char> buffer(copy.size() * 1024 + 1024);
    const int quads = stb_easy_font_print(0, 0, copy.data(), nullptr, buffer.data(),
                                          static_cast<int>(buffer.size()));
    const auto* v = reinterpret_cast<const float*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
        const float* corner[4];
        for (int k = 0; k < 4; ++k)
            corner[k] = v + (q * 4 + k) * 4;
        for (int k : {0, 1, 2, 0, 2, 3}) {
            xy.push_back(x + scale * corner[k][0]);
            xy.push_back(y + scale * corner[k][1]);
        }
    }
}

float text_width(std::string_view text, float scale) {
    // From the glyphs' own quads: stb_easy_font_width leaves out the last
    // glyph's right edge.
    std::vector<float> xy;
    append_text_triangles(text, 0, 0, scale, xy);
    float right = 0;
    for (std::size_t k = 0; k < xy.size(); k += 2)
        right = std::max(right, xy[k]);
    return right;
}

float text_height(std::string_view text, float scale) {
    std::string copy(text);
    return scale * float(stb_easy_font_height(copy.data()));
}

} // namespace sph
