#pragma once
// `--set KEY=VALUE`, as `run`, `study` and `validate` take it.

#include "scene/scene.hpp"

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace sph {

// Split at the first '=' (a value may hold more). Throws InputError naming
// --set for text without one.
Override parse_set(const std::string& key_value);
std::vector<Override> parse_sets(const std::vector<std::string>& key_values);

// The same check for --set values passed on to child runs as they are: a
// malformed one fails before any run starts.
void check_sets(const std::vector<std::string>& key_values);

// A command-line number that must be finite and above 0 (--duration, --fps):
// CLI11's PositiveNumber lets "nan" through, and NaN then fails every check.
CLI::Validator positive_finite_number();

} // namespace sph
