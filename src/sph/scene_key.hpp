#pragma once
// A scene key declared as data, next to the component that owns it: its
// path, the settings field it fills (a member pointer), its unit, bounds and
// one-line doc. Its default is the field's initialiser in the settings
// struct, written once. One table of keys per settings struct; scene/ walks the
// tables to read a scene with its checks, write run.json's `scene` and list
// the keys (`sphclip keys`), so this header knows nothing of JSON.

#include <array>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace sph {

using Vec3 = std::array<double, 3>;

// The range a number key must lie in.
enum class Bound { any, positive, non_negative, fraction }; // fraction: 0 to 1

// How many numbers a vector key holds: one per dimension of the scene, or fixed.
enum class VectorSize { dimension, two, three };

// An enumerated key's field, read and written as its index in Key::choices
// (the enum's values in the order of their names).
template <class S>
struct EnumField {
    int (*get)(const S&);
    void (*set)(S&, int);
};

// The field of S a key fills. A std::string field is a choice among
// Key::choices; an optional one is free text.
template <class S>
using KeyField =
    std::variant<double S::*, std::optional<double> S::*, int S::*, std::optional<int> S::*,
                 bool S::*, std::string S::*, std::optional<std::string> S::*, Vec3 S::*,
                 std::optional<Vec3> S::*, std::array<int, 2> S::*,
                 std::optional<std::array<double, 2>> S::*, EnumField<S>>;

template <class S>
struct Key {
    std::string path{}; // below its table's prefix ("" for the prefix itself)
    KeyField<S> field{};
    std::string unit{};
    std::string doc{};
    Bound bound = Bound::any;           // number keys
    int min = 0, max = 0;               // integer keys (and each number of an image size)
    std::vector<std::string> choices{}; // choice and enum keys: the values allowed
    std::string absent{};               // what an absent key means, where no value says it
    VectorSize size = VectorSize::dimension;
    bool nullable = false; // a value that may be null (absent): an effect that is off
    // In a list's element: a key without a default, that must be given
    // (`absent` says "required" for the docs).
    bool required = false;
    // A key for some values only (a paddle's motion's): given where it does
    // not apply, it is refused with `refused`, and it is not written there.
    bool (*applies)(const S&) = nullptr;
    std::string refused{};
    // A key of one dimension's scenes only (2 or 3; 0: both): a scene of the
    // other refuses it (with `refused`, else a problem naming the
    // dimension), rather than ignore it, and run.json's scene leaves it out.
    int only_dimension = 0;
};

template <class S>
using KeyTable = std::vector<Key<S>>;

// What a declared check finds wrong with a value: the key below the value's
// path (empty: the value itself) and the problem.
struct KeyProblem {
    std::string path;
    std::string problem;
};

// One of the objects a list's element may be, under its own key:
// {"box": {...}} or {"sphere": {...}}. Its keys' paths are below `key`.
template <class S>
struct Alternative {
    std::string key;
    int value = 0; // of the element's selector (KeyList::which)
    KeyTable<S> keys{};
    std::string missing{}; // the problem when a required key is absent
    int min_dimension = 2; // in fewer dimensions it is refused with...
    std::string too_few{}; // ...this problem
};

// A key whose value is a list of objects (effects.emitters), each read with
// `keys` and, where there are alternatives, as exactly one of them. Its
// default is the empty list.
template <class S>
struct KeyList {
    std::string path; // the whole path, "effects.emitters"
    std::string doc;
    KeyTable<S> keys{};
    std::vector<Alternative<S>> alternatives{};
    EnumField<S> which{};  // the alternative an element is, by Alternative::value
    std::string several{}; // the problem when an element gives more than one alternative
    std::string none{};    // ... and when it gives none
    // The element's keys against each other, once they are read.
    std::optional<KeyProblem> (*check)(const S&, int dimension) = nullptr;
};

template <class P>
struct MemberOf;
template <class S, class T>
struct MemberOf<T S::*> {
    using Struct = S;
    using Type = T;
};

// The EnumField of member M, an enum whose values are 0, 1, ... in the order
// of the key's choices.
template <auto M>
constexpr EnumField<typename MemberOf<decltype(M)>::Struct> enum_field() {
    using S = typename MemberOf<decltype(M)>::Struct;
    using E = typename MemberOf<decltype(M)>::Type;
    return {[](const S& s) { return static_cast<int>(s.*M); },
            [](S& s, int i) {
                s.*M = static_cast<E>(i);
            }};
}

// The EnumField of member M, a std::optional of such an enum whose first
// choice is "auto": nullopt, resolved from the rest of the scene.
template <auto M>
constexpr EnumField<typename MemberOf<decltype(M)>::Struct> auto_enum_field() {
    using S = typename MemberOf<decltype(M)>::Struct;
    using E = typename MemberOf<decltype(M)>::Type::value_type;
    return {[](const S& s) { return (s.*M) ? static_cast<int>(*(s.*M)) + 1 : 0; },
            [](S& s, int i) {
                s.*M = i == 0 ? std::optional<E>() : std::optional(static_cast<E>(i - 1));
            }};
}

} // namespace sph
