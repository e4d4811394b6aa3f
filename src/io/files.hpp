#pragma once
// File writing that never leaves a half-written file behind.

#include <filesystem>
#include <string_view>

namespace sph {

// Writes to a temporary name beside `path`, then renames: readers see the old
// file or the whole new one. Throws std::runtime_error naming the path.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

} // namespace sph
