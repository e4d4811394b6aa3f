// Equivalence of the neighbour searches with brute force (STYLE.md point 13),
// on random clouds in 2D and 3D, negative coordinates included.
#include "sph/neighbours/all_pairs.hpp"
#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <random>

using namespace sph;

namespace {

template <int D>
std::vector<Vec<D>> random_cloud(std::size_t n, Real lo, Real hi, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<Real> u(lo, hi);
    std::vector<Vec<D>> x(n);
    for (auto& p : x)
        for (int a = 0; a < D; ++a)
            p[a] = u(rng);
    return x;
}

std::vector<std::vector<std::uint32_t>> as_sorted_rows(const NeighbourList& list) {
    std::vector<std::vector<std::uint32_t>> rows(list.particle_count());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        auto row = list.of(i);
        rows[i].assign(row.begin(), row.end());
        std::sort(rows[i].begin(), rows[i].end());
    }
    return rows;
}

template <int D>
void check_equal_to_brute_force(const std::vector<Vec<D>>& x, Real radius) {
    NeighbourList expected, got;
    AllPairs<D>().find(x, radius, expected);
    SpatialHash<D> hash;
    hash.find(x, radius, got);
    REQUIRE(got.particle_count() == x.size());
    CHECK(got.pair_count() == expected.pair_count());
    CHECK(as_sorted_rows(got) == as_sorted_rows(expected));
    // Reusing the search and the list gives the same again.
    hash.find(x, radius, got);
    CHECK(as_sorted_rows(got) == as_sorted_rows(expected));
}

} // namespace

TEST_CASE("spatial hash equals brute force in 2D", "[neighbours]") {
    check_equal_to_brute_force<2>(random_cloud<2>(2000, 0, 1, 1), 0.05);
    // Negative coordinates, and a cloud straddling the origin.
    check_equal_to_brute_force<2>(random_cloud<2>(2000, -1, -0.2, 2), 0.04);
    check_equal_to_brute_force<2>(random_cloud<2>(2000, -0.5, 0.5, 3), 0.03);
    // Far from the origin.
    check_equal_to_brute_force<2>(random_cloud<2>(1000, 1e4, 1e4 + 1, 4), 0.05);
}

TEST_CASE("spatial hash equals brute force in 3D", "[neighbours]") {
    check_equal_to_brute_force<3>(random_cloud<3>(3000, 0, 1, 5), 0.12);
    check_equal_to_brute_force<3>(random_cloud<3>(3000, -1, -0.1, 6), 0.1);
    check_equal_to_brute_force<3>(random_cloud<3>(3000, -0.5, 0.5, 7), 0.1);
}

TEST_CASE("spatial hash handles degenerate clouds", "[neighbours]") {
    // Every particle in one cell, including coincident ones.
    auto x = random_cloud<2>(300, 0.1, 0.1001, 8);
    x.push_back(x[0]);
    x.push_back(x[0]);
    check_equal_to_brute_force<2>(x, 0.5);
    // A single particle has no neighbour; an empty cloud gives an empty list.
    NeighbourList list;
    SpatialHash<3> hash;
    hash.find(std::vector<Vec<3>>{Vec<3>(1, 2, 3)}, 0.1, list);
    CHECK(list.particle_count() == 1);
    CHECK(list.pair_count() == 0);
    hash.find(std::vector<Vec<3>>{}, 0.1, list);
    CHECK(list.particle_count() == 0);
    // Strictly closer than the radius: a pair at exactly the radius is not listed.
    hash.find(std::vector<Vec<3>>{Vec<3>(0, 0, 0), Vec<3>(0.25, 0, 0)}, 0.25, list);
    CHECK(list.pair_count() == 0);
}

TEST_CASE("neighbour lists are symmetric", "[neighbours]") {
    const auto x = random_cloud<3>(2000, -1, 1, 9);
    NeighbourList list;
    SpatialHash<3>().find(x, 0.15, list);
    for (std::size_t i = 0; i < x.size(); ++i)
        for (std::uint32_t j : list.of(i)) {
            auto row = list.of(j);
            CHECK(std::find(row.begin(), row.end(), i) != row.end());
        }
}
