// The vectorised row sums (sph/neighbours/neighbour_sum.hpp) and the padding
// every neighbour list ends in, which lets their loops read whole vectors
// past a row's end.
#include "sph/boundaries/boundary_particles.hpp"
#include "sph/neighbours/all_pairs.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

using namespace sph;

namespace {

std::vector<Vec<2>> random_cloud(std::size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(-1, 1);
    std::vector<Vec<2>> x(n);
    for (auto& p : x)
        p = {u(rng), u(rng)};
    return x;
}

// The padding: simd_lanes zeros after the last pair.
void check_padded(const NeighbourList& list) {
    REQUIRE(list.index.size() == list.pair_count() + simd_lanes);
    for (std::size_t e = list.pair_count(); e < list.index.size(); ++e)
        CHECK(list.index[e] == 0);
}

} // namespace

TEST_CASE("every neighbour list ends in a vector's width of padding", "[neighbours]") {
    const auto x = random_cloud(500, 1);
    NeighbourList list;
    SECTION("all pairs") {
        AllPairs<2>().find(x, 0.1, list);
    }
    SECTION("hash") {
        SpatialHash<2>().find(x, 0.1, list);
    }
    SECTION("sorted grid") {
        SortedGrid<2>().find(x, 0.1, list);
    }
    SECTION("sorted grid, radius 0") {
        SortedGrid<2>().find(x, 0, list);
    }
    SECTION("sorted grid, reused for fewer pairs") {
        SortedGrid<2> grid;
        grid.find(x, 0.3, list);
        grid.find(x, 0.05, list);
    }
    SECTION("wall particles") {
        BoundaryParticles<2> walls(random_cloud(200, 2), 0.1, Real(1e-3));
        walls.find_neighbours(x, list);
        CHECK(list.pair_count() > 0);
    }
    REQUIRE(list.particle_count() == x.size());
    check_padded(list);
}

TEST_CASE("row sums over neighbours equal plain sums, rows of every length", "[neighbours]") {
    // Row lengths 0 .. 3 vector widths, so every remainder is met, and the
    // last row reads into the padding.
    const auto x = random_cloud(400, 3);
    NeighbourList list;
    SortedGrid<2>().find(x, 0.2, list); // about 12 neighbours, 0 to 30
    std::vector<Real> value(x.size());
    for (std::size_t i = 0; i < x.size(); ++i)
        value[i] = 1 + Real(i % 7) / 3;
    std::vector<bool> remainder_seen(simd_lanes, false);
    std::size_t longest = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        Real plain = 0;
        Vec<2> plain_vector(0);
        for (std::uint32_t j : list.of(i)) {
            plain += value[j];
            plain_vector += value[j] * (x[i] - x[j]);
        }
        const Real summed = sum_over_neighbours(list, i, [&](std::uint32_t j) { return value[j]; });
        const Vec<2> summed_vector =
            sum_over_neighbours(list, i, [&](std::uint32_t j) { return value[j] * (x[i] - x[j]); });
        CHECK(summed == Approx(plain).epsilon(1e-14));
        CHECK(summed_vector.x == Approx(plain_vector.x).margin(1e-14));
        CHECK(summed_vector.y == Approx(plain_vector.y).margin(1e-14));
        // Per-pair arrays: the pair's place e.
        const Real by_place = sum_over_pairs(
            list, i, [&](std::size_t e, std::uint32_t j) { return Real(e) + 0 * value[j]; });
        Real places = 0;
        for (std::size_t e = list.start[i]; e < list.start[i + 1]; ++e)
            places += Real(e);
        CHECK(by_place == places);
        const std::size_t length = list.of(i).size();
        remainder_seen[length % simd_lanes] = true;
        longest = std::max(longest, length);
    }
    // Every remainder after whole vectors was met, and rows of several vectors.
    CHECK(std::count(remainder_seen.begin(), remainder_seen.end(), true) == simd_lanes);
    CHECK(longest > 2 * simd_lanes);
}

TEST_CASE("3D row sums equal plain sums", "[neighbours]") {
    std::mt19937 rng(4);
    std::uniform_real_distribution<Real> u(0, 1);
    std::vector<Vec<3>> x(600);
    for (auto& p : x)
        p = {u(rng), u(rng), u(rng)};
    NeighbourList list;
    SortedGrid<3>().find(x, 0.15, list);
    for (std::size_t i = 0; i < x.size(); ++i) {
        Vec<3> plain(0);
        for (std::uint32_t j : list.of(i))
            plain += x[i] - x[j];
        const Vec<3> summed =
            sum_over_neighbours(list, i, [&](std::uint32_t j) { return x[i] - x[j]; });
        for (int a = 0; a < 3; ++a)
            CHECK(summed[a] == Approx(plain[a]).margin(1e-13));
    }
}
