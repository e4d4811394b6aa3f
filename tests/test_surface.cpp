// Buried-particle detection: interior of a block yes; its surface and the
// layer below no, even when the fluid is compressed.
#include "sph/neighbours/spatial_hash.hpp"
#include "sph/surface.hpp"

#include <catch2/catch.hpp>
#include <random>

using namespace sph;

namespace {

// A cube of side n at `spacing`; returns the flags.
std::vector<std::uint8_t> cube_flags(int n, double spacing, double h, double lattice_spacing) {
    State<3> state;
    state.resize(std::size_t(n) * n * n);
    std::size_t k = 0;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z)
                state.position[k++] = Vec<3>(x, y, z) * spacing;
    NeighbourList list;
    SpatialHash<3>().find(state.position, h, list);
    std::vector<std::uint8_t> buried;
    mark_buried(state, list, lattice_spacing, buried);
    return buried;
}

int depth(int i, int n) {
    return std::min(i, n - 1 - i);
}

} // namespace

TEST_CASE("only particles deep inside a block are buried", "[surface]") {
    for (double squeeze : {1.0, 0.8}) { // at rest, and compressed to 80% spacing
        const int n = 12;
        const double s = 0.01;
        const auto buried = cube_flags(n, squeeze * s, 2.2 * s, s);
        std::size_t k = 0, count = 0;
        for (int x = 0; x < n; ++x)
            for (int y = 0; y < n; ++y)
                for (int z = 0; z < n; ++z, ++k) {
                    const int d = std::min({depth(x, n), depth(y, n), depth(z, n)});
                    INFO("squeeze " << squeeze << " depth " << d);
                    if (d <= 1) // the surface and the layer below it are always drawn
                        CHECK(buried[k] == 0);
                    if (d >= 3) // deep inside: hidden
                        CHECK(buried[k] == 1);
                    count += buried[k];
                }
        CHECK(count > 0);
    }
}

TEST_CASE("a jittered block still keeps its surface", "[surface]") {
    // Particles displaced at random by up to 30% of the spacing.
    const int n = 12;
    const double s = 0.01;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-0.3 * s, 0.3 * s);
    State<3> state;
    state.resize(std::size_t(n) * n * n);
    std::size_t k = 0;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z)
                state.position[k++] =
                    Vec<3>(x * s + jitter(rng), y * s + jitter(rng), z * s + jitter(rng));
    NeighbourList list;
    SpatialHash<3>().find(state.position, 2.2 * s, list);
    std::vector<std::uint8_t> buried;
    mark_buried(state, list, s, buried);
    k = 0;
    std::size_t deep = 0, deep_buried = 0;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z, ++k) {
                const int d = std::min({depth(x, n), depth(y, n), depth(z, n)});
                if (d == 0)
                    CHECK(buried[k] == 0);
                if (d >= 3) {
                    ++deep;
                    deep_buried += buried[k];
                }
            }
    // Most of the deep interior is still recognised.
    CHECK(deep_buried > deep / 2);
}
