#include "analysis/study_plan.hpp"

#include "scene/input_error.hpp"

#include <fmt/format.h>
#include <set>

namespace sph {

namespace {

[[noreturn]] void bad_vary(std::string_view text, const std::string& problem) {
    throw InputError("command line", "--vary",
                     fmt::format("{} in \"{}\" (expected KEY=V1,V2,...)", problem, text));
}

} // namespace

Variation parse_variation(std::string_view text) {
    const std::size_t eq = text.find('=');
    if (eq == std::string_view::npos)
        bad_vary(text, "no '='");
    Variation variation;
    variation.key = std::string(text.substr(0, eq));
    if (variation.key.empty())
        bad_vary(text, "no key");
    const std::string_view list = text.substr(eq + 1);
    int depth = 0;
    std::string value;
    auto finish_value = [&] {
        if (value.empty())
            bad_vary(text, "an empty value");
        variation.values.push_back(value);
        value.clear();
    };
    for (char c : list) {
        if (c == '[' || c == '{')
            ++depth;
        else if (c == ']' || c == '}')
            --depth;
        if (c == ',' && depth == 0)
            finish_value();
        else
            value += c;
    }
    if (depth != 0)
        bad_vary(text, "unbalanced brackets");
    finish_value();
    std::set<std::string> seen;
    for (const auto& v : variation.values)
        if (!seen.insert(v).second)
            bad_vary(text, fmt::format("the value {} listed twice", v));
    return variation;
}

std::vector<Combination> expand_combinations(const std::vector<Variation>& variations) {
    std::set<std::string> keys;
    for (const auto& v : variations)
        if (!keys.insert(v.key).second)
            throw InputError(
                "command line", "--vary",
                fmt::format("{} is varied twice; list all its values in one --vary", v.key));
    std::vector<Combination> combinations{{}};
    for (const auto& variation : variations) {
        std::vector<Combination> longer;
        for (const auto& partial : combinations)
            for (const auto& value : variation.values) {
                longer.push_back(partial);
                longer.back().emplace_back(variation.key, value);
            }
        combinations = std::move(longer);
    }
    return combinations;
}

std::string run_folder_name(std::size_t index, std::size_t count, const Combination& combination) {
    const std::size_t width =
        std::max<std::size_t>(2, fmt::format("{}", count ? count - 1 : 0).size());
    std::string name = fmt::format("{:0{}}", index, width);
    for (const auto& [key, value] : combination)
        name += "_" + key + "=" + value;
    for (char& c : name) {
        const bool plain = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                           (c >= '0' && c <= '9') || c == '.' || c == '_' || c == '=' || c == '+' ||
                           c == '-';
        if (!plain)
            c = '_';
    }
    return name;
}

std::optional<std::size_t> finest_run(const std::vector<RunSize>& runs) {
    std::optional<std::size_t> best;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        if (!runs[i].usable)
            continue;
        if (!best || runs[i].particles > runs[*best].particles ||
            (runs[i].particles == runs[*best].particles && runs[i].dt < runs[*best].dt))
            best = i;
    }
    return best;
}

} // namespace sph
