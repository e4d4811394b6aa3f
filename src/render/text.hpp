#pragma once
// Labels drawn as geometry: stb_easy_font turns text into quads, which become
// triangles in pixel coordinates (origin at the top left, y down).

#include <string_view>
#include <vector>

namespace sph {

// Appends x, y pairs (two triangles per quad) for `text` at (x, y), each
// glyph pixel `scale` pixels wide.
void append_text_triangles(std::string_view text, float x, float y, float scale,
                           std::vector<float>& xy);

// Width and height in pixels of `text` at `scale`.
float text_width(std::string_view text, float scale);
float text_height(std::string_view text, float scale);

} // namespace sph
