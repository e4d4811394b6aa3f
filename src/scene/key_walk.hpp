#pragma once
// Walks a table of declared keys (sph/scene_key.hpp) over a scene's JSON:
// reading fills a settings struct with the checks of FieldReader and records
// each key for `sphclip keys`; writing gives run.json's `scene`. The tables
// say what the keys are; this file is all that knows how they look in JSON.

#include "scene/field_reader.hpp"
#include "sph/scene_key.hpp"

#include <type_traits>

// GCC 12 follows every member pointer of a key's variant into every settings
// struct, the small ones included, and warns of reads past them on branches
// the variant's index never takes.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#pragma GCC diagnostic ignored "-Wstringop-overread"
#endif

namespace sph {

// prefix + "." + path, either of them possibly empty.
inline std::string key_path(const std::string& prefix, const std::string& path) {
    return prefix.empty() ? path : path.empty() ? prefix : prefix + "." + path;
}

inline int vector_size(VectorSize size, int dimension) {
    return size == VectorSize::two ? 2 : size == VectorSize::three ? 3 : dimension;
}

// Reads one key into `out`; absent (or null), it takes its value from `fallback`.
template <class S>
void read_key(FieldReader& r, const std::string& prefix, const Key<S>& key, const S& fallback,
              S& out, int dimension) {
    const std::string path = key_path(prefix, key.path);
    const int n = vector_size(key.size, dimension);
    auto shown = [&](const std::string& value) {
        return key.absent.empty() ? value : key.absent;
    };
    auto choice_doc = [&] {
        return fmt::format("{} One of: {}.", key.doc, fmt::join(key.choices, ", "));
    };
    if (key.only_dimension != 0 && key.only_dimension != dimension && r.present(path))
        r.fail(path, key.refused.empty() ? fmt::format("is a {}D key; this scene is {}D",
                                                       key.only_dimension, dimension)
                                         : key.refused);
    const json* v = r.find(path);
    std::visit(
        [&](auto field) {
            using F = decltype(field);
            if constexpr (std::is_same_v<F, double S::*>) {
                r.record(path, "number", key.unit, shown(fmt::format("{}", fallback.*field)),
                         key.doc);
                out.*field = v ? r.checked_number(path, *v, key.bound) : fallback.*field;
            } else if constexpr (std::is_same_v<F, std::optional<double> S::*>) {
                r.record(path, "number or null", key.unit, key.absent, key.doc);
                out.*field =
                    v ? std::optional(r.checked_number(path, *v, key.bound)) : fallback.*field;
            } else if constexpr (std::is_same_v<F, int S::*>) {
                r.record(path, "integer", key.unit, shown(std::to_string(fallback.*field)),
                         key.doc);
                out.*field = v ? r.checked_integer(path, *v, key.min, key.max) : fallback.*field;
            } else if constexpr (std::is_same_v<F, std::optional<int> S::*>) {
                r.record(path, "integer or null", key.unit, key.absent, key.doc);
                out.*field = v ? std::optional(r.checked_integer(path, *v, key.min, key.max))
                               : fallback.*field;
            } else if constexpr (std::is_same_v<F, bool S::*>) {
                r.record(path, "true or false", key.unit, fallback.*field ? "true" : "false",
                         key.doc);
                out.*field = v ? r.checked_boolean(path, *v) : fallback.*field;
            } else if constexpr (std::is_same_v<F, std::string S::*>) {
                r.record(path, "string", key.unit, shown(fallback.*field), choice_doc());
                out.*field = v ? r.checked_choice(path, *v, key.choices) : fallback.*field;
            } else if constexpr (std::is_same_v<F, EnumField<S>>) {
                r.record(path, "string", key.unit, shown(key.choices[field.get(fallback)]),
                         choice_doc());
                if (v) {
                    const std::string text = r.checked_choice(path, *v, key.choices);
                    const auto at = std::find(key.choices.begin(), key.choices.end(), text);
                    field.set(out, static_cast<int>(at - key.choices.begin()));
                } else {
                    field.set(out, field.get(fallback));
                }
            } else if constexpr (std::is_same_v<F, std::optional<std::string> S::*>) {
                r.record(path, "string", key.unit, key.absent, key.doc);
                out.*field = v ? std::optional(r.checked_text(path, *v)) : fallback.*field;
            } else if constexpr (std::is_same_v<F, Vec3 S::*>) {
                r.record(path,
                         fmt::format("array of {} numbers{}", n, key.nullable ? " or null" : ""),
                         key.unit, shown(format_vector(fallback.*field, n)), key.doc);
                out.*field = v ? r.checked_vector(path, *v, n) : fallback.*field;
            } else if constexpr (std::is_same_v<F, std::optional<Vec3> S::*>) {
                r.record(path, fmt::format("array of {} numbers or null", n), key.unit, key.absent,
                         key.doc);
                out.*field = v ? std::optional(r.checked_vector(path, *v, n)) : fallback.*field;
            } else if constexpr (std::is_same_v<F, std::array<int, 2> S::*>) {
                const auto& d = fallback.*field;
                r.record(path, "array of 2 integers", key.unit,
                         shown(fmt::format("[{}, {}]", d[0], d[1])), key.doc);
                out.*field = v ? r.checked_image_size(path, *v, key.min, key.max) : d;
            } else {
                static_assert(std::is_same_v<F, std::optional<std::array<double, 2>> S::*>);
                r.record(path, "array of 2 numbers or null", key.unit, key.absent, key.doc);
                if (v) {
                    const Vec3 pair = r.checked_vector(path, *v, 2);
                    out.*field = std::array<double, 2>{pair[0], pair[1]};
                } else {
                    out.*field = fallback.*field;
                }
            }
        },
        key.field);
}

// Reads every key of `table` under `prefix`.
template <class S>
void read_keys(FieldReader& r, const std::string& prefix, const KeyTable<S>& table,
               const S& fallback, S& out, int dimension) {
    for (const Key<S>& key : table)
        read_key(r, prefix, key, fallback, out, dimension);
}

template <class S>
S read_keys(FieldReader& r, const std::string& prefix, const KeyTable<S>& table, const S& fallback,
            int dimension) {
    S out = fallback;
    read_keys(r, prefix, table, fallback, out, dimension);
    return out;
}

// Writes every key of `table` into `node` (an object, or for a key with an
// empty path the value itself), as read_keys reads them back.
template <class S>
void write_keys(json& node, const KeyTable<S>& table, const S& value, int dimension) {
    for (const Key<S>& key : table) {
        if ((key.applies && !key.applies(value)) ||
            (key.only_dimension != 0 && key.only_dimension != dimension))
            continue;
        json& out = key.path.empty() ? node : node[key.path];
        const int n = vector_size(key.size, dimension);
        auto vector = [n](const Vec3& v) {
            return std::vector<double>(v.begin(), v.begin() + n);
        };
        std::visit(
            [&](auto field) {
                using F = decltype(field);
                if constexpr (std::is_same_v<F, EnumField<S>>) {
                    out = key.choices[field.get(value)];
                } else if constexpr (std::is_same_v<F, Vec3 S::*>) {
                    out = vector(value.*field);
                } else if constexpr (std::is_same_v<F, std::optional<Vec3> S::*>) {
                    out = value.*field ? json(vector(*(value.*field))) : json();
                } else {
                    const auto& x = value.*field;
                    if constexpr (requires { x.has_value(); })
                        out = x ? json(*x) : json();
                    else
                        out = x;
                }
            },
            key.field);
    }
}

template <class S>
json write_keys(const KeyTable<S>& table, const S& value, int dimension) {
    json node = json::object();
    write_keys(node, table, value, dimension);
    return node;
}

// Reads the list `list` (absent: empty). Each element's keys are read and
// checked, then `finish(element, path)` does what needs more than the keys
// (a mesh's file), before the next element is read. With no list the keys of
// one element are still read, for the documentation.
template <class S, class Finish>
std::vector<S> read_list(FieldReader& r, const KeyList<S>& list, int dimension, Finish&& finish) {
    const std::size_t count = r.list(list.path, "none", list.doc.c_str());
    std::vector<S> out;
    const S fallback{};
    for (std::size_t i = 0; i < std::max<std::size_t>(count, 1); ++i) {
        const std::string p = fmt::format("{}[{}]", list.path, i);
        const bool real = i < count;
        S element = read_keys(r, p, list.keys, fallback, dimension);
        // An alternative not given is still read (its keys are recorded),
        // into a scratch copy: alternatives may share fields.
        S scratch = fallback;
        for (const Alternative<S>& alternative : list.alternatives) {
            const std::string path = p + "." + alternative.key;
            const bool given = r.present(path);
            if (real && dimension < alternative.min_dimension && given)
                r.fail(path, alternative.too_few);
            read_keys(r, path, alternative.keys, fallback, given ? element : scratch, dimension);
        }
        if (!real)
            break;
        std::string prefix = p; // where the element's keys are: p, or its alternative's
        const KeyTable<S>* keys = &list.keys;
        std::string missing;
        if (!list.alternatives.empty()) {
            const Alternative<S>* chosen = nullptr;
            int given = 0;
            for (const Alternative<S>& alternative : list.alternatives)
                if (r.present(p + "." + alternative.key) && given++ == 0)
                    chosen = &alternative;
            if (given != 1)
                r.fail(p, given > 1 ? list.several : list.none);
            prefix = p + "." + chosen->key;
            if (const json* v = r.find(prefix); !v->is_object())
                r.fail(prefix, "expected an object, got " + describe(*v));
            list.which.set(element, chosen->value);
            keys = &chosen->keys;
            missing = chosen->missing;
        }
        for (const Key<S>& key : *keys)
            if (key.required && !r.present(key_path(prefix, key.path)))
                r.fail(key_path(prefix, key.path), missing.empty() ? "is required" : missing);
        for (const Key<S>& key : list.keys)
            if (key.applies && !key.applies(element) && r.present(key_path(p, key.path)))
                r.fail(key_path(p, key.path), key.refused);
        if (list.check)
            if (const auto problem = list.check(element, dimension))
                r.fail(key_path(p, problem->path), problem->problem);
        finish(element, prefix);
        out.push_back(std::move(element));
    }
    return out;
}

template <class S>
std::vector<S> read_list(FieldReader& r, const KeyList<S>& list, int dimension) {
    return read_list(r, list, dimension, [](S&, const std::string&) {});
}

// The elements as read_list reads them back; an absent value (null) is left out.
template <class S>
json write_list(const KeyList<S>& list, const std::vector<S>& elements, int dimension) {
    json out = json::array();
    for (const S& element : elements) {
        json node = write_keys(list.keys, element, dimension);
        for (const Alternative<S>& alternative : list.alternatives)
            if (list.which.get(element) == alternative.value)
                node[alternative.key] = write_keys(alternative.keys, element, dimension);
        for (auto it = node.begin(); it != node.end();)
            it = it->is_null() ? node.erase(it) : std::next(it);
        out.push_back(std::move(node));
    }
    return out;
}

} // namespace sph

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
