#include "cli/data_folders.hpp"

#include "cli/child_process.hpp"
#include "io/input_error.hpp"

#include <fmt/format.h>
#include <string>
#include <vector>

namespace sph {

namespace fs = std::filesystem;

namespace {

fs::path first_folder(const std::vector<fs::path>& candidates, const std::string& what,
                      const std::string& option) {
    std::vector<std::string> tried;
    for (const auto& c : candidates) {
        std::error_code ec;
        if (fs::is_directory(c, ec))
            return fs::weakly_canonical(c, ec);
        tried.push_back(c.lexically_normal().string());
    }
    throw InputError("command line", option,
                     fmt::format("cannot find the {}; tried {}; give it with {}", what,
                                 fmt::join(tried, ", "), option));
}

fs::path program_folder() {
    try {
        return self_executable().parent_path();
    } catch (const fs::filesystem_error&) {
        return {};
    }
}

} // namespace

fs::path find_scenes_folder() {
    std::vector<fs::path> candidates{fs::current_path() / "scenes"};
    if (const auto exe = program_folder(); !exe.empty())
        candidates.push_back(exe / ".." / "scenes");
    return first_folder(candidates, "scenes folder", "--scenes-dir");
}

fs::path find_reference_folder() {
    const fs::path cwd = fs::current_path();
    std::vector<fs::path> candidates{cwd / ".." / "shared" / "reference",
                                     cwd / ".." / ".." / "shared" / "reference"};
    if (const auto exe = program_folder(); !exe.empty()) {
        candidates.push_back(exe / ".." / ".." / "shared" / "reference");
        candidates.push_back(exe / ".." / ".." / ".." / "shared" / "reference");
    }
    return first_folder(candidates, "reference data folder", "--reference-dir");
}

} // namespace sph
