// The torture suite (tests/stability/): every case with every solver, checked
// after every frame (stability/torture.cpp). Issue: "test that hard cases stay
// numerically stable".
#include "sph/solvers/solver.hpp"
#include "stability/torture.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <set>

using namespace sph;
namespace fs = std::filesystem;

TEST_CASE("every scene under tests/stability is a torture case", "[stability]") {
    std::set<std::string> listed, found;
    for (const auto& c : torture::cases())
        listed.insert(c.scene);
    for (const auto& entry : fs::directory_iterator(SPHCLIP_STABILITY_DIR))
        if (entry.path().extension() == ".json")
            found.insert(entry.path().filename().string());
    CHECK(listed == found);
}

namespace {

void check_case(const std::string& scene) {
    const auto& all = torture::cases();
    const auto c = std::find_if(all.begin(), all.end(),
                                [&](const torture::Case& k) { return k.scene == scene; });
    REQUIRE(c != all.end());
    for (const auto& solver : solver_names()) {
        INFO(scene << " / " << solver);
        const auto r = torture::run(SPHCLIP_STABILITY_DIR, *c, solver);
        for (const auto& f : r.failures)
            UNSCOPED_INFO(f);
        for (const auto& f : r.warnings)
            UNSCOPED_INFO("physics: " << f);
        if (!r.stop.empty())
            UNSCOPED_INFO("stopped: " << r.stop);
        CHECK(r.passed(*c));
        CHECK(r.steps > 0);
    }
}

} // namespace

// One test per case, so that ctest runs them side by side.
#define TORTURE_CASE(name)                                                                         \
    TEST_CASE("torture: " name " stays stable with every solver", "[stability]") {                 \
        check_case(name ".json");                                                                  \
    }

TORTURE_CASE("coincident_pair")
TORTURE_CASE("duplicated_block")
TORTURE_CASE("compressed_start")
TORTURE_CASE("sparse_start")
TORTURE_CASE("impact_20ms")
TORTURE_CASE("tall_drop")
TORTURE_CASE("stiff")
TORTURE_CASE("viscous")
TORTURE_CASE("single_particle")
TORTURE_CASE("lone_particle")
TORTURE_CASE("thin_sheet")
TORTURE_CASE("far_from_origin")
TORTURE_CASE("negative_coordinates")
TORTURE_CASE("one_cell")
TORTURE_CASE("tank_at_rest")
TORTURE_CASE("deep_tank_3d")
TORTURE_CASE("drop_3d")
