// The key walk (src/scene/key_walk.hpp) over lists of objects (KeyList): an
// element is exactly one of its alternatives, a required key must be given, a
// key for some values only is refused elsewhere and not written, the
// element's declared check names its field, and the list is written as it is
// read back, absent values left out.

#include "scene/input_error.hpp"
#include "scene/key_walk.hpp"

#include <catch2/catch.hpp>
#include <optional>
#include <string>

namespace {

using namespace sph;

enum class Kind { round, square };

struct Thing {
    Kind kind = Kind::round;
    double size = 1;
    std::optional<double> tag;
    double spin = 0; // square only
};

const KeyList<Thing>& thing_keys() {
    static const KeyTable<Thing> round_keys{
        {.path = "size", .field = &Thing::size, .absent = "required", .required = true}};
    static const KeyTable<Thing> square_keys{{.path = "size", .field = &Thing::size}};
    static const KeyTable<Thing> common{
        {.path = "tag", .field = &Thing::tag},
        {.path = "spin",
         .field = &Thing::spin,
         .applies = [](const Thing& t) { return t.kind == Kind::square; },
         .refused = "is for squares"}};
    static const KeyList<Thing> keys{.path = "things",
                                     .doc = "Things.",
                                     .keys = common,
                                     .alternatives = {{.key = "round",
                                                       .value = 0,
                                                       .keys = round_keys,
                                                       .missing = "needs a size"},
                                                      {.key = "square",
                                                       .value = 1,
                                                       .keys = square_keys,
                                                       .min_dimension = 3,
                                                       .too_few = "a square is 3D"}},
                                     .which = enum_field<&Thing::kind>(),
                                     .several = "one of round or square",
                                     .none = "expected round or square",
                                     .check = [](const Thing& t, int) -> std::optional<KeyProblem> {
                                         if (t.tag && *t.tag > t.size)
                                             return KeyProblem{"tag", "above the size"};
                                         return std::nullopt;
                                     }};
    return keys;
}

std::vector<Thing> read(const json& root, int dimension = 3) {
    FieldReader r(root, "things.json", {});
    return read_list(r, thing_keys(), dimension);
}

// The field a read fails on, "" when it reads.
std::string failing_field(const json& root, int dimension = 3) {
    try {
        read(root, dimension);
        return "";
    } catch (const InputError& e) {
        return e.field;
    }
}

} // namespace

TEST_CASE("a list's element is one alternative, with its required keys", "[scene][keys]") {
    const auto things = read(json::parse(
        R"({"things": [{"round": {"size": 2}, "tag": 1}, {"square": {}, "spin": 3}]})"));
    REQUIRE(things.size() == 2);
    CHECK(things[0].kind == Kind::round);
    CHECK(things[0].size == 2);
    CHECK(things[0].tag == 1);
    CHECK(things[1].kind == Kind::square);
    CHECK(things[1].size == 1); // the default where the key is not required
    CHECK(things[1].spin == 3);
    CHECK(read(json::object()).empty());

    CHECK(failing_field(json::parse(R"({"things": [{"round": {}}]})")) == "things[0].round.size");
    CHECK(failing_field(json::parse(R"({"things": [{}]})")) == "things[0]");
    CHECK(failing_field(json::parse(R"({"things": [{"round": {"size": 1}, "square": {}}]})")) ==
          "things[0]");
    CHECK(failing_field(json::parse(R"({"things": [{"round": 5}]})")) == "things[0].round");
    CHECK(failing_field(json::parse(R"({"things": [{"square": {}}]})"), 2) == "things[0].square");
    CHECK(failing_field(json::parse(R"({"things": [{"round": {"size": 1}, "spin": 1}]})")) ==
          "things[0].spin");
    CHECK(failing_field(json::parse(R"({"things": [{"round": {"size": 1}, "tag": 2}]})")) ==
          "things[0].tag");
}

TEST_CASE("a list is written as it reads back", "[scene][keys]") {
    const json given = json::parse(
        R"({"things": [{"round": {"size": 2}}, {"square": {"size": 4}, "tag": 1, "spin": 3}]})");
    const json written = write_list(thing_keys(), read(given), 3);
    // The round one has no tag (left out, not null) and no spin (not its key).
    CHECK(written[0] == json::parse(R"({"round": {"size": 2.0}})"));
    CHECK(written[1] == json::parse(R"({"square": {"size": 4.0}, "tag": 1.0, "spin": 3.0})"));
    CHECK(write_list(thing_keys(), read(json{{"things", written}}), 3) == written);
}
