// Paths named in a scene stay inside their folder (src/scene/scene_paths.cpp).

#include "scene/input_error.hpp"
#include "scene/scene_paths.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <optional>
#include <string>

namespace {

namespace fs = std::filesystem;

std::optional<sph::InputError> refusal(const std::string& relative) {
    try {
        sph::resolve_inside("out", relative, "scene.json", "output.name");
    } catch (const sph::InputError& e) {
        return e;
    }
    return std::nullopt;
}

} // namespace

TEST_CASE("a plain relative path resolves inside its base folder", "[scene]") {
    CHECK(sph::resolve_inside("out", "run", "scene.json", "output.name") == fs::path("out/run"));
    CHECK(sph::resolve_inside("out", "a/b", "f", "k") == fs::path("out/a/b"));
    CHECK(sph::resolve_inside("out", "a/./b", "f", "k") == fs::path("out/a/b"));
    CHECK(sph::resolve_inside("out", "./a", "f", "k") == fs::path("out/a"));
    CHECK(sph::resolve_inside("out", "a/", "f", "k") == fs::path("out/a"));
    CHECK(sph::resolve_inside("out", "a b..c", "f", "k") == fs::path("out/a b..c"));
    CHECK(sph::resolve_inside("/data/scenes", "meshes/cup.obj", "f", "k") ==
          fs::path("/data/scenes/meshes/cup.obj"));
}

TEST_CASE("a path that leaves its base folder is bad input naming file and field", "[scene]") {
    struct Case {
        std::string relative, problem;
    };
    const auto bad = GENERATE(values<Case>({
        {"/tmp/escape", "absolute"},
        {"/", "absolute"},
        {"..", "\"..\""},
        {"../escape", "\"..\""},
        {"a/../../b", "\"..\""},
        {"a/../b", "\"..\""}, // stays inside, but ".." is refused outright
        {"a/..", "\"..\""},
        {"", "empty"},
        {".", "itself"},
        {"./", "itself"},
        {"a/..b/\n", "control character"},
        {std::string("a\0/../../etc", 12), "control character"},
        {std::string(256, 'x'), "longer than 255 bytes"},
    }));
    INFO("relative = \"" << bad.relative << "\"");
    const auto e = refusal(bad.relative);
    REQUIRE(e);
    CHECK(e->file == "scene.json");
    CHECK(e->field == "output.name");
    CHECK(std::string(e->problem).find(bad.problem) != std::string::npos);
    CHECK(std::string(e->problem).find("inside out/") != std::string::npos);
}

TEST_CASE("a long refused path is shortened in the message", "[scene]") {
    const auto e = refusal("../" + std::string(10000, 'x'));
    REQUIRE(e);
    CHECK(e->problem.size() < 200);
    CHECK(e->problem.find("10003 bytes") != std::string::npos);
}
