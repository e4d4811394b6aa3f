#include "cli/data_folders.hpp"

#include "cli/child_process.hpp"
#include "scene/input_error.hpp"

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
    if (const auto exe = program_folder(); !exe.empty()) {
        candidates.push_back(exe / ".." / "scenes");
        candidates.push_back(exe / ".." / "share" / "sphclip" / "scenes"); // installed
    }
    return first_folder(candidates, "scenes folder", "--scenes-dir");
}

fs::path find_reference_folder() {
    // The repository's data/reference beside scenes/, from the current folder
    // or from the program's (build/sphclip); then the installed copy.
    std::vector<fs::path> candidates{fs::current_path() / "data" / "reference"};
    if (const auto exe = program_folder(); !exe.empty()) {
        candidates.push_back(exe / ".." / "data" / "reference");
        candidates.push_back(exe / ".." / "share" / "sphclip" / "data" / "reference");
    }
    return first_folder(candidates, "reference data folder", "--reference-dir");
}

} // namespace sph
