#include "scene/scene_paths.hpp"

#include "scene/input_error.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

// Longest file name on Linux file systems (NAME_MAX).
constexpr std::size_t max_name_bytes = 255;

// The path as messages quote it: a hostile one can be long.
std::string quoted(const std::string& text) {
    return text.size() <= 60 ? fmt::format("\"{}\"", text)
                             : fmt::format("\"{}...\" ({} bytes)", text.substr(0, 57), text.size());
}

} // namespace

fs::path resolve_inside(const fs::path& base, const std::string& relative, const std::string& file,
                        const std::string& field) {
    auto refuse = [&](const std::string& why) {
        throw InputError(file, field,
                         fmt::format("{} must be a relative path inside {}/, but {}",
                                     quoted(relative), base.string(), why));
    };
    if (relative.empty())
        refuse("it is empty");
    // A NUL would cut the name short in every system call; other control
    // characters make names that cannot be typed or listed safely.
    if (std::any_of(relative.begin(), relative.end(),
                    [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        refuse("it holds a control character");
    const fs::path path(relative);
    if (path.has_root_path())
        refuse("it is absolute");
    for (const auto& part : path) {
        if (part == "..")
            refuse("it climbs out with \"..\"");
        if (part.native().size() > max_name_bytes)
            refuse(fmt::format("a name in it is longer than {} bytes", max_name_bytes));
    }
    // "a/./b" is "a/b"; "." or "./" is the base folder itself, shared by every run.
    fs::path normal = path.lexically_normal();
    if (!normal.empty() && !normal.has_filename())
        normal = normal.parent_path(); // "a/b/" -> "a/b"
    if (normal.empty() || normal == ".")
        refuse(fmt::format("it names {}/ itself", base.string()));
    return base / normal;
}

} // namespace sph
