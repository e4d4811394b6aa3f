#include "cli/set_options.hpp"

#include "scene/input_error.hpp"

#include <cmath>
#include <cstdlib>
#include <fmt/format.h>

namespace sph {

Override parse_set(const std::string& key_value) {
    const auto eq = key_value.find('=');
    if (eq == std::string::npos)
        throw InputError("command line", "--set",
                         fmt::format("expected KEY=VALUE, got \"{}\"", key_value));
    return {key_value.substr(0, eq), key_value.substr(eq + 1)};
}

std::vector<Override> parse_sets(const std::vector<std::string>& key_values) {
    std::vector<Override> overrides;
    for (const auto& key_value : key_values)
        overrides.push_back(parse_set(key_value));
    return overrides;
}

void check_sets(const std::vector<std::string>& key_values) {
    for (const auto& key_value : key_values)
        parse_set(key_value);
}

CLI::Validator positive_finite_number() {
    return CLI::Validator(
        [](std::string& input) -> std::string {
            char* end = nullptr;
            const double value = std::strtod(input.c_str(), &end);
            if (input.empty() || *end != '\0' || !std::isfinite(value) || !(value > 0))
                return fmt::format("{} is not a finite number above 0", input);
            return {};
        },
        "POSITIVE");
}

} // namespace sph
