#pragma once
// Where `validate` and `study` find the shipped scenes and the reference data
// when the command line does not say.

#include <filesystem>

namespace sph {

// scenes/ in the current folder, else beside the program's folder
// (build/sphclip -> build/../scenes), the layout of a build in the
// repository, else ../share/sphclip/scenes from it (an installed program:
// /usr/bin/sphclip -> /usr/share/sphclip/scenes). Throws InputError naming
// the places tried.
std::filesystem::path find_scenes_folder();

// The reference tables, shipped in the repository's data/reference/ (each
// file names its source in its header): tried from the current folder as
// data/reference, then from the program's folder as ../data/reference (the
// build folder in a clone) and ../share/sphclip/data/reference (an
// installed program). Throws InputError naming the places tried and
// --reference-dir.
std::filesystem::path find_reference_folder();

} // namespace sph
