#pragma once
// `sphclip compare REF.png TEST.png`: checks a rendered image against a
// reference one within tolerances (README, "Using sphclip compare in CI").

#include "io/image_compare.hpp"

#include <string>

namespace CLI {
class App;
}

namespace sph {

struct CompareCliOptions {
    std::string reference;     // REF.png
    std::string test;          // TEST.png
    CompareOptions thresholds; // --tolerance, --threshold, --max-different
    std::string diff;          // --diff: where to write the difference image; empty: nowhere
};

// Adds the `compare` subcommand to `app`; parsing fills `options`.
CLI::App* add_compare_command(CLI::App& app, CompareCliOptions& options);

// Prints the metrics on stdout and returns the exit code: 0 when the images
// match, 1 when they differ. Throws InputError for an unreadable image,
// images of different sizes, or a --diff that cannot be written.
int compare_command(const CompareCliOptions& options);

} // namespace sph
