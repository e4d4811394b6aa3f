#pragma once
// Reading a scene's JSON by dotted path ("fluid.blocks[2].min") with type and
// range checks whose messages name the file and the field. Every key asked
// for is recorded, for the unknown-key check and `sphclip keys`.

#include "scene/input_error.hpp"
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

using nlohmann::json;

// The candidate nearest to `word` if it is plausibly a typo of it, else "".
std::string closest(std::string_view word, const std::vector<std::string>& candidates);
// A value's type and its first characters, for messages: "string (\"abc\")".
std::string describe(const json& value);
// A string from the scene as messages quote it: a hostile one can be long.
std::string shortened(const std::string& text);
// "fluid.blocks[3].min" -> "fluid.blocks[].min": the key's place in the schema.
std::string generic_path(const std::string& path);
// "a.b" encloses "a.b", "a.b.c" and "a.b[2]".
bool encloses(const std::string& outer, const std::string& inner);
std::string parent_of(const std::string& path);
std::string last_segment(const std::string& path);
// "[x, y]" or "[x, y, z]": the first `dimension` components.
std::string format_vector(const Vec3& v, int dimension);

// Reads fields by dotted path with type and range checks. Every key it is
// asked for is recorded: the reading code is the schema, so the unknown-key
// check and `sphclip keys` cannot drift from it.
class FieldReader {
  public:
    FieldReader(const json& root, std::string file, std::set<std::string> overridden)
        : root_(root), file_(std::move(file)), overridden_(std::move(overridden)) {}

    [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
        const bool from_command_line =
            std::any_of(overridden_.begin(), overridden_.end(), [&](const std::string& key) {
                return encloses(key, path) || encloses(path, key);
            });
        throw InputError(file_, path + (from_command_line ? " (from --set)" : ""), problem);
    }

    // nullptr when absent (or null).
    const json* find(const std::string& path) const {
        const json* node = &root_;
        std::size_t begin = 0;
        while (begin <= path.size()) {
            std::size_t end = path.find('.', begin);
            if (end == std::string::npos)
                end = path.size();
            std::string segment = path.substr(begin, end - begin);
            std::optional<std::size_t> index;
            if (auto bracket = segment.find('['); bracket != std::string::npos) {
                index = std::stoul(segment.substr(bracket + 1));
                segment.resize(bracket);
            }
            if (!node->is_object())
                return nullptr;
            auto it = node->find(segment);
            if (it == node->end() || it->is_null())
                return nullptr;
            node = &*it;
            if (index) {
                if (!node->is_array() || *index >= node->size())
                    return nullptr;
                node = &(*node)[*index];
            }
            begin = end + 1;
        }
        return node;
    }

    double number(const std::string& path, double fallback, const char* unit, const char* doc,
                  Bound bound = Bound::any) {
        record(path, "number", unit, fmt::format("{}", fallback), doc);
        const json* v = find(path);
        return v ? checked_number(path, *v, bound) : fallback;
    }

    std::optional<double> optional_number(const std::string& path, const char* unit,
                                          const std::string& default_text, const char* doc,
                                          Bound bound = Bound::any) {
        record(path, "number or null", unit, default_text, doc);
        const json* v = find(path);
        return v ? std::optional(checked_number(path, *v, bound)) : std::nullopt;
    }

    int integer(const std::string& path, int fallback, int min, int max, const char* doc) {
        record(path, "integer", "", std::to_string(fallback), doc);
        const json* v = find(path);
        return v ? checked_integer(path, *v, min, max) : fallback;
    }

    bool boolean(const std::string& path, bool fallback, const char* doc) {
        record(path, "true or false", "", fallback ? "true" : "false", doc);
        const json* v = find(path);
        if (!v)
            return fallback;
        if (!v->is_boolean())
            fail(path, "expected true or false, got " + describe(*v));
        return v->get<bool>();
    }

    std::string choice(const std::string& path, const std::string& fallback,
                       const std::vector<std::string>& allowed, const char* doc) {
        record(path, "string", "", fallback,
               fmt::format("{} One of: {}.", doc, fmt::join(allowed, ", ")));
        const json* v = find(path);
        return v ? checked_choice(path, *v, allowed) : fallback;
    }

    std::optional<std::string> optional_text(const std::string& path,
                                             const std::string& default_text, const char* doc) {
        record(path, "string", "", default_text, doc);
        const json* v = find(path);
        if (!v)
            return std::nullopt;
        if (!v->is_string())
            fail(path, "expected a string, got " + describe(*v));
        return v->get<std::string>();
    }

    Vec3 vector(const std::string& path, const Vec3& fallback, int dimension, const char* unit,
                const char* doc) {
        record(path, fmt::format("array of {} numbers", dimension), unit,
               format_vector(fallback, dimension), doc);
        const json* v = find(path);
        return v ? checked_vector(path, *v, dimension) : fallback;
    }

    std::optional<Vec3> optional_vector(const std::string& path, int dimension, const char* unit,
                                        const std::string& default_text, const char* doc) {
        record(path, fmt::format("array of {} numbers or null", dimension), unit, default_text,
               doc);
        const json* v = find(path);
        return v ? std::optional(checked_vector(path, *v, dimension)) : std::nullopt;
    }

    std::array<int, 2> image_size(const std::string& path, std::array<int, 2> fallback,
                                  const char* doc) {
        record(path, "array of 2 integers", "px", fmt::format("[{}, {}]", fallback[0], fallback[1]),
               doc);
        const json* v = find(path);
        return v ? checked_image_size(path, *v, 1, 16384) : fallback;
    }

    // A list of objects; returns the element count (0 when absent).
    std::size_t list(const std::string& path, const std::string& default_text, const char* doc) {
        record(path, "array of objects", "", default_text, doc);
        const json* v = find(path);
        if (!v)
            return 0;
        if (!v->is_array())
            fail(path, "expected an array, got " + describe(*v));
        for (std::size_t i = 0; i < v->size(); ++i)
            if (!(*v)[i].is_object())
                fail(fmt::format("{}[{}]", path, i),
                     "expected an object, got " + describe((*v)[i]));
        return v->size();
    }

    bool present(const std::string& path) const { return find(path) != nullptr; }

    bool is_object_key(const std::string& path) const {
        const auto prefix = path + ".";
        return std::any_of(known_.begin(), known_.end(),
                           [&](const std::string& k) { return k.starts_with(prefix); });
    }

    // Names the first key in the scene that no reader asked for.
    void reject_unknown_keys() const { check_object(root_, ""); }

    const std::vector<KeyDoc>& docs() const { return docs_; }

    // Notes a key for the unknown-key check and `sphclip keys`.
    void record(const std::string& path, std::string type, const std::string& unit,
                std::string default_value, std::string doc) {
        const auto generic = generic_path(path);
        if (known_.insert(generic).second)
            docs_.push_back(
                {generic, std::move(type), unit, std::move(default_value), std::move(doc)});
    }

    // The value at `path` converted, or the message naming path and problem.
    double checked_number(const std::string& path, const json& v, Bound bound) const {
        if (!v.is_number())
            fail(path, "expected a number, got " + describe(v));
        const double x = v.get<double>();
        if (!std::isfinite(x))
            fail(path, "expected a finite number");
        if (bound == Bound::positive && !(x > 0))
            fail(path, fmt::format("must be greater than 0, got {}", x));
        if (bound == Bound::non_negative && x < 0)
            fail(path, fmt::format("must not be negative, got {}", x));
        if (bound == Bound::fraction && !(x >= 0 && x <= 1))
            fail(path, fmt::format("must be between 0 and 1, got {}", x));
        return x;
    }

    int checked_integer(const std::string& path, const json& v, int min, int max) const {
        if (!v.is_number())
            fail(path, "expected an integer, got " + describe(v));
        const double x = v.get<double>();
        if (x != std::floor(x))
            fail(path, fmt::format("expected an integer, got {}", x));
        if (x < min || x > max)
            fail(path, fmt::format("must be between {} and {}, got {}", min, max, x));
        return static_cast<int>(x);
    }

    Vec3 checked_vector(const std::string& path, const json& v, int dimension) const {
        if (!v.is_array() || static_cast<int>(v.size()) != dimension)
            fail(path, fmt::format("expected an array of {} numbers (the scene is {}D), got {}",
                                   dimension, dimension, describe(v)));
        Vec3 out{0, 0, 0};
        for (int a = 0; a < dimension; ++a) {
            const std::string element = fmt::format("{}[{}]", path, a);
            if (!v[a].is_number())
                fail(element, "expected a number, got " + describe(v[a]));
            out[a] = v[a].get<double>();
            if (!std::isfinite(out[a]))
                fail(element, "expected a finite number");
        }
        return out;
    }

    std::string checked_choice(const std::string& path, const json& v,
                               const std::vector<std::string>& allowed) const {
        if (!v.is_string())
            fail(path, "expected a string, got " + describe(v));
        const auto text = v.get<std::string>();
        if (std::find(allowed.begin(), allowed.end(), text) == allowed.end()) {
            const auto guess = closest(text, allowed);
            fail(path,
                 fmt::format("unknown value \"{}\"{}; expected one of: {}", shortened(text),
                             guess.empty() ? "" : fmt::format(" (did you mean \"{}\"?)", guess),
                             fmt::join(allowed, ", ")));
        }
        return text;
    }

    std::string checked_text(const std::string& path, const json& v) const {
        if (!v.is_string())
            fail(path, "expected a string, got " + describe(v));
        return v.get<std::string>();
    }

    bool checked_boolean(const std::string& path, const json& v) const {
        if (!v.is_boolean())
            fail(path, "expected true or false, got " + describe(v));
        return v.get<bool>();
    }

    std::array<int, 2> checked_image_size(const std::string& path, const json& v, int min,
                                          int max) const {
        if (!v.is_array() || v.size() != 2)
            fail(path, "expected an array of 2 integers [width, height], got " + describe(v));
        return {checked_integer(path, v[0], min, max), checked_integer(path, v[1], min, max)};
    }

  private:
    void check_object(const json& object, const std::string& prefix) const {
        for (auto it = object.begin(); it != object.end(); ++it) {
            const std::string path = prefix.empty() ? it.key() : prefix + "." + it.key();
            if (it.key().find_first_of("[]") != std::string::npos)
                reject(path, path); // brackets only ever come from list indices
            const std::string generic = generic_path(path);
            if (known_.contains(generic)) {
                if (it->is_array() && is_list(generic))
                    for (std::size_t i = 0; i < it->size(); ++i)
                        check_object((*it)[i], fmt::format("{}[{}]", path, i));
                continue;
            }
            if (is_object_key(generic)) {
                if (it->is_object())
                    check_object(*it, path);
                else if (!it->is_null())
                    fail(path, "expected an object, got " + describe(*it));
                continue;
            }
            reject(path, generic);
        }
    }

    bool is_list(const std::string& generic) const {
        const auto prefix = generic + "[].";
        return std::any_of(known_.begin(), known_.end(),
                           [&](const std::string& k) { return k.starts_with(prefix); });
    }

    [[noreturn]] void reject(const std::string& path, const std::string& generic) const {
        // Suggest among the keys beside it first, then anywhere in the scene.
        const std::string parent = parent_of(generic);
        std::vector<std::string> siblings, all;
        for (const auto& k : known_) {
            all.push_back(k);
            if (parent_of(k) == parent)
                siblings.push_back(last_segment(k));
        }
        for (const auto& k : known_) // groups are keys too
            for (std::string p = parent_of(k); !p.empty(); p = parent_of(p))
                if (parent_of(p) == parent)
                    siblings.push_back(last_segment(p));
        std::string guess = closest(last_segment(generic), siblings);
        if (!guess.empty())
            guess = parent.empty() ? guess : parent_of(path) + "." + guess;
        else
            guess = closest(generic, all);
        fail(path, "unknown key" + (guess.empty() ? std::string()
                                                  : fmt::format(" (did you mean '{}'?)", guess)));
    }

    const json& root_;
    std::string file_;
    std::set<std::string> overridden_;
    std::set<std::string> known_;
    std::vector<KeyDoc> docs_;
};

} // namespace sph
