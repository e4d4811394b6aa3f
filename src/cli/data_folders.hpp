#pragma once
// Where `validate` and `study` find the shipped scenes and the reference data
// when the command line does not say.

#include <filesystem>

namespace sph {

// scenes/ in the current folder, else beside the program's folder
// (build/sphclip -> build/../scenes), the layout of a build in the
// repository. Throws InputError naming the places tried.
std::filesystem::path find_scenes_folder();

// The reference tables (../shared/reference beside the repository): tried
// from the current folder as ../shared/reference and ../../shared/reference,
// then from the program's folder as ../../shared/reference and
// ../../../shared/reference. Throws InputError naming the places tried and
// --reference-dir.
std::filesystem::path find_reference_folder();

} // namespace sph
