#pragma once
// The overlay's font files: which one a run uses, and whether one the user
// named can be used. No OpenGL here, so that the command line can check a
// font before anything is written. Defined in text.cpp, beside the glyphs.

#include <string>
#include <vector>

namespace sph {

// The font file to use: `requested` (render.font) when it names a readable
// file; else the first readable of default_font_paths(); else what
// fontconfig's `fc-match` names for "DejaVu Sans"; else empty (the bitmap
// font). Why a choice was not taken goes to `warning` (empty: none).
std::string find_font(const std::string& requested, std::string& warning);
// Why FreeType cannot draw with `font_file` (render.font): it is not a
// regular file within output/files.hpp's font_file_limit, or not a font; empty
// when it can. A run asks before it writes anything.
std::string font_problem(const std::string& font_file);
// Where Debian (fonts-dejavu-core), Fedora and Arch put DejaVu Sans.
const std::vector<std::string>& default_font_paths();

} // namespace sph
