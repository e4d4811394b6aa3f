#pragma once
// Paths that a scene file names (the output folder's name; obstacle meshes
// later) stay inside the folder they are relative to, so that a scene from
// elsewhere cannot make sphclip write or read outside it.

#include <filesystem>
#include <string>

namespace sph {

// `base / relative`, when `relative` is a plain relative path that stays
// inside `base`: not empty, not absolute, no ".." component, not `base`
// itself, no control character, no name over 255 bytes. Otherwise throws
// InputError(file, field, why). The check is on the text alone: a symbolic
// link already inside `base` is the user's own and is followed.
std::filesystem::path resolve_inside(const std::filesystem::path& base, const std::string& relative,
                                     const std::string& file, const std::string& field);

} // namespace sph
