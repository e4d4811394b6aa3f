#pragma once
// `sphclip compare REF.png TEST.png`: checks a rendered image against a
// reference one within tolerances (README, "Using sphclip compare in CI").

#include "output/image_compare.hpp"

#include <string>

namespace CLI {
class App;
}

namespace sph {

struct CompareCliOptions {
    std::string reference;     // REF.png, or a folder of references
    std::string test;          // TEST.png, or a folder of images to check
    CompareOptions thresholds; // --tolerance, --threshold, --max-different, --max-pixels
    std::string diff;          // --diff: where to write the difference image (a folder in
                               // folder mode); empty: nowhere
    bool json = false;         // --json: the report as JSON on stdout instead of text
    bool update = false;       // --update: copy TEST over REF where they differ
};

// Adds the `compare` subcommand to `app`; parsing fills `options`.
CLI::App* add_compare_command(CLI::App& app, CompareCliOptions& options);

// Prints the metrics on stdout and returns the exit code: 0 when the images
// match, 1 when they differ. Throws InputError for an unreadable image,
// images of different sizes, or a --diff that cannot be written. With two
// folders, compares the PNGs they share by name and reports the rest
// (docs: "Image checks in CI").
int compare_command(const CompareCliOptions& options);

} // namespace sph
