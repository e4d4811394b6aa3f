#pragma once
// PNG plots drawn by gnuplot (Debian gnuplot-nox). The script is kept beside
// the image, NAME.gp for NAME.png, so a plot can be redrawn or restyled by
// hand: `cd FOLDER && gnuplot NAME.gp`.

#include <filesystem>
#include <string>

namespace sph {

// Writes NAME.gp (a PNG terminal, then `commands`) beside `png` and runs
// gnuplot in that folder, so the commands name data files relative to it.
// pngcairo (antialiased) when this gnuplot has it, else the libgd png
// terminal. A plot is a convenience next to the CSV that holds the numbers:
// when gnuplot is missing or fails this prints a warning and returns false.
bool plot_png(const std::filesystem::path& png, const std::string& commands);

// A string as a gnuplot single-quoted literal.
std::string gnuplot_quote(const std::string& text);

} // namespace sph
