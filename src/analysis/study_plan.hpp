#pragma once
// What `sphclip study` runs: the cartesian product of the --vary lists, each
// combination a run in a folder named after it; and which run is the finest,
// the reference when no validation case applies.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sph {

struct Variation {
    std::string key;                 // dotted scene path, as for --set
    std::vector<std::string> values; // in the order given
};

// One run: a value for every varied key, in --vary order.
using Combination = std::vector<std::pair<std::string, std::string>>;

// "KEY=V1,V2,...". Commas inside brackets or braces belong to the value, so a
// vector can be varied: "fluid.blocks.0.velocity=[1,0],[2,0]". Throws
// InputError (command line, --vary) for a missing key, '=' or value.
Variation parse_variation(std::string_view text);

// Every combination, the last --vary changing fastest (like nested loops in
// --vary order). Throws InputError when a key is varied twice.
std::vector<Combination> expand_combinations(const std::vector<Variation>& variations);

// "<index>_<key=value>_<key=value>...", the index zero-padded to the width of
// `count - 1` (at least 2 digits) so that folders list in run order;
// characters other than letters, digits and ._=+- become '_'.
std::string run_folder_name(std::size_t index, std::size_t count, const Combination& combination);

struct RunSize {
    bool usable = false; // completed; an unstable or failed run is never the reference
    std::size_t particles = 0;
    double dt = 0; // mean time step over the frames, s
};

// The finest run: the most particles; among equals the smallest mean time
// step (a smaller CFL number or fixed dt); then the first. None when no run
// is usable.
std::optional<std::size_t> finest_run(const std::vector<RunSize>& runs);

} // namespace sph
