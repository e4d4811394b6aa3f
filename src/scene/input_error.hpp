#pragma once
// Bad input (scene file, --set, command line, output folder): one message that
// names the file and the field. The program maps it to exit code 2. The
// message shows control characters escaped (scene/printable.hpp).

#include "scene/printable.hpp"

#include <stdexcept>
#include <string>

namespace sph {

struct InputError : std::runtime_error {
    std::string file;  // the scene file, or "command line"
    std::string field; // dotted path of the field, may be empty
    std::string problem;
    InputError(std::string file_, std::string field_, std::string problem_)
        : std::runtime_error(
              printable(file_ + ": " + (field_.empty() ? "" : field_ + ": ") + problem_)),
          file(std::move(file_)), field(std::move(field_)), problem(std::move(problem_)) {}
};

} // namespace sph
