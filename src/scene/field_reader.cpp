#include "scene/field_reader.hpp"

namespace sph {

namespace {

// Levenshtein distance, for "did you mean" suggestions.
std::size_t edit_distance(std::string_view a, std::string_view b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diagonal = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t above = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
            diagonal = above;
        }
    }
    return row[b.size()];
}

} // namespace

std::string closest(std::string_view word, const std::vector<std::string>& candidates) {
    // Only suggest what is plausibly a typo.
    const std::size_t limit = std::max<std::size_t>(2, word.size() / 2);
    std::string best;
    std::size_t best_distance = std::string::npos;
    for (const auto& c : candidates) {
        // The distance is at least the difference in length: a long hostile
        // word is not compared letter by letter with every key.
        const std::size_t shortest =
            std::max(word.size(), c.size()) - std::min(word.size(), c.size());
        if (shortest > limit)
            continue;
        const std::size_t d = edit_distance(word, c);
        if (d < best_distance) {
            best_distance = d;
            best = c;
        }
    }
    return best_distance <= limit ? best : std::string();
}

// Compact JSON text of `value`, stopped soon after `limit` characters: a huge
// or deeply nested value is neither serialised whole nor recursed into deeper
// than the limit (each level adds a bracket).
static void append_short(const json& value, std::string& out, std::size_t limit) {
    if (!value.is_structured()) {
        // A --set string need not be UTF-8: replaced, not thrown on.
        out += value.dump(-1, ' ', false, json::error_handler_t::replace);
        return;
    }
    const bool array = value.is_array();
    out += array ? '[' : '{';
    for (auto it = value.begin(); it != value.end() && out.size() <= limit; ++it) {
        if (it != value.begin())
            out += ',';
        if (!array)
            out += json(it.key()).dump(-1, ' ', false, json::error_handler_t::replace) + ':';
        append_short(*it, out, limit);
    }
    out += array ? ']' : '}';
}

std::string describe(const json& value) {
    std::string text;
    append_short(value, text, 40);
    if (text.size() > 40)
        text = text.substr(0, 37) + "...";
    return fmt::format("{} ({})", value.type_name(), text);
}

// A string from the scene as messages quote it: a hostile one can be long.
std::string shortened(const std::string& text) {
    return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

// "fluid.blocks[3].min" -> "fluid.blocks[].min": the key's place in the schema.
// By hand, not std::regex (slow, and recursive per character): it runs for
// every key of every block.
std::string generic_path(const std::string& path) {
    std::string out;
    out.reserve(path.size());
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i] == '[') {
            std::size_t end = i + 1;
            while (end < path.size() && path[end] >= '0' && path[end] <= '9')
                ++end;
            if (end > i + 1 && end < path.size() && path[end] == ']') {
                out += "[]";
                i = end;
                continue;
            }
        }
        out += path[i];
    }
    return out;
}

// "a.b" encloses "a.b", "a.b.c" and "a.b[2]".
bool encloses(const std::string& outer, const std::string& inner) {
    return inner.starts_with(outer) && (inner.size() == outer.size() ||
                                        inner[outer.size()] == '.' || inner[outer.size()] == '[');
}

std::string parent_of(const std::string& path) {
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? std::string() : path.substr(0, dot);
}

std::string last_segment(const std::string& path) {
    const auto dot = path.rfind('.');
    return dot == std::string::npos ? path : path.substr(dot + 1);
}

std::string format_vector(const Vec3& v, int dimension) {
    return fmt::format("[{}]", fmt::join(v.begin(), v.begin() + dimension, ", "));
}

} // namespace sph
