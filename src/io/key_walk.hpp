#pragma once
// Walks a table of declared keys (sph/scene_key.hpp) over a scene's JSON:
// reading fills a settings struct with the checks of FieldReader and records
// each key for `sphclip keys`; writing gives run.json's `scene`. The tables
// say what the keys are; this file is all that knows how they look in JSON.

#include "io/field_reader.hpp"
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

} // namespace sph

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
