// Equivalence of the neighbour searches with brute force (STYLE.md point 13),
// on random clouds and lattices in 2D and 3D, negative coordinates included;
// the sorted grid also with 1 and 2 threads.
#include "sph/boundaries/boundary_particles.hpp"
#include "sph/neighbours/all_pairs.hpp"
#include "sph/neighbours/cell_neighbourhoods.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/neighbours/spatial_hash.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numeric>
#include <omp.h>
#include <random>
#include <tuple>

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

// A lattice of side^D particles at spacing dp from `origin`, stored in a
// random order (as in CompactNSearch's benchmark).
template <int D>
std::vector<Vec<D>> shuffled_lattice(std::size_t side, Real dp, Real origin, unsigned seed) {
    std::vector<Vec<D>> x;
    const std::size_t n = D == 2 ? side * side : side * side * side;
    for (std::size_t k = 0; k < n; ++k) {
        Vec<D> p;
        std::size_t rest = k;
        for (int a = 0; a < D; ++a, rest /= side)
            p[a] = origin + (Real(rest % side) + 0.5) * dp;
        x.push_back(p);
    }
    std::shuffle(x.begin(), x.end(), std::mt19937(seed));
    return x;
}

bool rows_ascending(const NeighbourList& list) {
    for (std::size_t i = 0; i < list.particle_count(); ++i) {
        auto row = list.of(i);
        if (!std::is_sorted(row.begin(), row.end()) ||
            std::adjacent_find(row.begin(), row.end()) != row.end())
            return false;
    }
    return true;
}

// The sorted grid lists exactly the pairs brute force and the hash list, each
// row already ascending. (The hash is left out for cell coordinates past
// 64-bit integers, which it does not handle.)
template <int D>
void check_sorted_grid(const std::vector<Vec<D>>& x, Real radius, bool with_hash = true) {
    NeighbourList expected, hashed, got;
    AllPairs<D>().find(x, radius, expected);
    SortedGrid<D> grid;
    grid.find(x, radius, got);
    REQUIRE(got.particle_count() == x.size());
    CHECK(got.pair_count() == expected.pair_count());
    CHECK(rows_ascending(got));
    CHECK(as_sorted_rows(got) == as_sorted_rows(expected));
    if (with_hash) {
        SpatialHash<D>().find(x, radius, hashed);
        CHECK(as_sorted_rows(got) == as_sorted_rows(hashed));
    }
    // The cell order is a permutation of the particles.
    std::vector<std::uint32_t> order = grid.order();
    std::sort(order.begin(), order.end());
    std::vector<std::uint32_t> identity(x.size());
    std::iota(identity.begin(), identity.end(), 0u);
    CHECK(order == identity);
    // Reusing the search and the list gives the same again.
    grid.find(x, radius, got);
    CHECK(as_sorted_rows(got) == as_sorted_rows(expected));
}

// The sorted grid's lists and cell order with the given number of threads.
template <int D>
auto lists_with_threads(int threads, const std::vector<Vec<D>>& x, Real radius) {
    omp_set_num_threads(threads);
    SortedGrid<D> grid;
    NeighbourList list;
    grid.find(x, radius, list);
    return std::tuple(list.start, list.index, grid.order());
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

TEST_CASE("sorted grid neighbours equal brute force and the hash in 2D", "[neighbours]") {
    check_sorted_grid<2>(random_cloud<2>(2000, 0, 1, 1), 0.05);
    check_sorted_grid<2>(random_cloud<2>(2000, -1, -0.2, 2), 0.04);
    check_sorted_grid<2>(random_cloud<2>(2000, -0.5, 0.5, 3), 0.03);
    // Far from the origin, on both sides.
    check_sorted_grid<2>(random_cloud<2>(1000, 1e4, 1e4 + 1, 4), 0.05);
    check_sorted_grid<2>(random_cloud<2>(1000, -1e4 - 1, -1e4, 5), 0.05);
    // Lattices: radius 2.6 spacings (20 neighbours), and exactly 2 spacings,
    // where the pairs at exactly the radius must be left out as brute force does.
    check_sorted_grid<2>(shuffled_lattice<2>(40, 0.01, 0, 6), 0.026);
    check_sorted_grid<2>(shuffled_lattice<2>(40, 1.0 / 64, -0.3, 7), 2.0 / 64);
    check_sorted_grid<2>(shuffled_lattice<2>(30, 0.001, 1e4, 8), 0.0026);
}

TEST_CASE("sorted grid neighbours equal brute force and the hash in 3D", "[neighbours]") {
    check_sorted_grid<3>(random_cloud<3>(3000, 0, 1, 9), 0.12);
    check_sorted_grid<3>(random_cloud<3>(3000, -1, -0.1, 10), 0.1);
    check_sorted_grid<3>(random_cloud<3>(3000, -0.5, 0.5, 11), 0.1);
    check_sorted_grid<3>(random_cloud<3>(1000, 1e4, 1e4 + 1, 12), 0.15);
    check_sorted_grid<3>(random_cloud<3>(1000, -1e4 - 1, -1e4, 13), 0.15);
    check_sorted_grid<3>(shuffled_lattice<3>(14, 1.0 / 128, 0, 14), 2.0 / 128);
    check_sorted_grid<3>(shuffled_lattice<3>(12, 0.01, -5, 15), 0.022);
    check_sorted_grid<3>(shuffled_lattice<3>(10, 0.001, -1e4, 16), 0.002);
}

TEST_CASE("sorted grid neighbours of degenerate clouds", "[neighbours]") {
    // Every particle in one cell, including coincident ones.
    auto one_cell = random_cloud<3>(300, 0.1, 0.1001, 17);
    one_cell.push_back(one_cell[0]);
    one_cell.push_back(one_cell[0]);
    check_sorted_grid<3>(one_cell, 0.5);
    // A single particle has no neighbour; an empty cloud gives an empty list.
    NeighbourList list;
    SortedGrid<3> grid;
    grid.find(std::vector<Vec<3>>{Vec<3>(1, 2, 3)}, 0.1, list);
    CHECK(list.particle_count() == 1);
    CHECK(list.pair_count() == 0);
    CHECK(grid.order() == std::vector<std::uint32_t>{0});
    grid.find(std::vector<Vec<3>>{}, 0.1, list);
    CHECK(list.particle_count() == 0);
    CHECK(grid.order().empty());
    // Strictly closer than the radius.
    grid.find(std::vector<Vec<3>>{Vec<3>(0, 0, 0), Vec<3>(0.25, 0, 0)}, 0.25, list);
    CHECK(list.pair_count() == 0);
    // Coincident particles only, and a radius of zero.
    SortedGrid<2> grid2;
    NeighbourList list2;
    grid2.find(std::vector<Vec<2>>(5, Vec<2>(-3, 7)), 0.1, list2);
    CHECK(list2.pair_count() == 20);
    grid2.find(std::vector<Vec<2>>(5, Vec<2>(-3, 7)), 0, list2);
    CHECK(list2.particle_count() == 5);
    CHECK(list2.pair_count() == 0);
}

TEST_CASE("finite_bounds: the box of the finite positions only", "[neighbours]") {
    const Real inf = std::numeric_limits<Real>::infinity();
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    // Enough positions for both threads to see some.
    std::vector<Vec<3>> positions = random_cloud<3>(1000, -2.0, 3.0, 5);
    positions.push_back(Vec<3>(-1e300, 0, 0)); // finite: counts
    positions.push_back(Vec<3>(nan, -100, 100));
    positions.push_back(Vec<3>(-inf, inf, 0.5));
    const Box<3> box = finite_bounds<3>(positions);
    Vec<3> lo(inf), hi(-inf);
    for (const auto& x : positions)
        for (int a = 0; a < 3; ++a)
            if (std::isfinite(x[a])) {
                lo[a] = std::min(lo[a], x[a]);
                hi[a] = std::max(hi[a], x[a]);
            }
    CHECK(box.min == lo);
    CHECK(box.max == hi);
    CHECK(box.min.x == -1e300);
    CHECK(box.min.y == -100); // the NaN's neighbours on other axes count
    // Nothing finite, or nothing at all: an empty box (min > max).
    for (const auto& none : {std::vector<Vec<2>>{}, std::vector<Vec<2>>(3, Vec<2>(nan, inf))}) {
        const Box<2> empty = finite_bounds<2>(none);
        CHECK(empty.min.x > empty.max.x);
        CHECK(empty.min.y > empty.max.y);
    }
}

TEST_CASE("sorted grid neighbours stay exact over huge and sparse boxes", "[neighbours]") {
    // A stray particle far away: too many cells for a table, so the occupied
    // cells are hashed.
    auto stray = random_cloud<3>(800, -1, 1, 18);
    stray.push_back(Vec<3>(300, 0, 0));
    SortedGrid<3> grid;
    NeighbourList list;
    grid.find(stray, 0.15, list);
    CHECK(grid.hashed_cells());
    check_sorted_grid<3>(stray, 0.15);
    // Wider than 2^21 cells along x and in 2D along both axes: coarser cells
    // there, still exact.
    auto huge = random_cloud<3>(800, 0, 1, 19);
    huge.push_back(Vec<3>(1e9, 0.5, 0.5));
    huge.push_back(Vec<3>(1e9 + 0.01, 0.5, 0.5));
    check_sorted_grid<3>(huge, 0.1);
    auto huge2 = random_cloud<2>(800, -1, 1, 20);
    huge2.push_back(Vec<2>(1e15, -1e15));
    huge2.push_back(Vec<2>(-1e300, 1e300));
    check_sorted_grid<2>(huge2, 0.05, false);
    // A dense box of the same particles uses the table.
    grid.find(random_cloud<3>(800, -1, 1, 18), 0.15, list);
    CHECK_FALSE(grid.hashed_cells());
    // Non-finite positions are nobody's neighbour and do not disturb the rest.
    auto broken = random_cloud<2>(500, 0, 1, 21);
    broken[3] = Vec<2>(std::nan(""), 0.5);
    broken[7] = Vec<2>(std::numeric_limits<Real>::infinity(), 0.5);
    check_sorted_grid<2>(broken, 0.05, false);
}

TEST_CASE("sorted grid neighbour lists are the same with 1 and 2 threads", "[neighbours]") {
    const int before = omp_get_max_threads();
    const auto x3 = shuffled_lattice<3>(20, 0.01, -0.1, 22);
    const auto x2 = random_cloud<2>(20000, -1, 1, 23);
    const auto one3 = lists_with_threads<3>(1, x3, 0.02), two3 = lists_with_threads<3>(2, x3, 0.02);
    const auto one2 = lists_with_threads<2>(1, x2, 0.02), two2 = lists_with_threads<2>(2, x2, 0.02);
    omp_set_num_threads(before);
    CHECK(one3 == two3);
    CHECK(one2 == two2);
}

TEST_CASE("sorted grid neighbours: particles stored in cell order stay in place", "[neighbours]") {
    // What a spatial sort of the particle arrays by order() relies on: sorting
    // again changes nothing, and the lists are the same up to renaming.
    const auto x = shuffled_lattice<3>(16, 0.01, 0, 24);
    SortedGrid<3> grid;
    NeighbourList list, sorted_list;
    grid.find(x, 0.02, list);
    const std::vector<std::uint32_t> order = grid.order();
    std::vector<Vec<3>> sorted(x.size());
    std::vector<std::uint32_t> rank(x.size());
    for (std::size_t k = 0; k < x.size(); ++k) {
        sorted[k] = x[order[k]];
        rank[order[k]] = static_cast<std::uint32_t>(k);
    }
    grid.find(sorted, 0.02, sorted_list);
    std::vector<std::uint32_t> identity(x.size());
    std::iota(identity.begin(), identity.end(), 0u);
    CHECK(grid.order() == identity);
    bool same = true;
    for (std::size_t i = 0; i < x.size(); ++i) {
        std::vector<std::uint32_t> renamed;
        for (std::uint32_t j : list.of(i))
            renamed.push_back(rank[j]);
        std::sort(renamed.begin(), renamed.end());
        auto row = sorted_list.of(rank[i]);
        same = same && std::vector<std::uint32_t>(row.begin(), row.end()) == renamed;
    }
    CHECK(same);
    // Nothing is reallocated when the particles move a little.
    const auto* index = sorted_list.index.data();
    const auto* order_data = grid.order().data();
    for (auto& p : sorted)
        p += Vec<3>(0.0004, -0.0003, 0.0002);
    grid.find(sorted, 0.02, sorted_list);
    CHECK(sorted_list.index.data() == index);
    CHECK(grid.order().data() == order_data);
}

TEST_CASE("sorted grid: a find after cell_order and the sort it asks for sorts nothing, and "
          "lists what a fresh search lists",
          "[neighbours]") {
    // The run loop's order: cell_order, the particle arrays permuted by it,
    // then the step's find, which reuses the grid (sorted_in_place). Its
    // lists must be a fresh grid's, bit for bit; and positions that are not
    // the sorted ones (one particle moved, or one fewer) must be sorted anew.
    const auto x = shuffled_lattice<3>(12, 0.01, 0, 31);
    const Real radius = 0.021;
    const auto permuted = [&](SortedGrid<3>& grid) {
        const std::span<const std::uint32_t> order = grid.cell_order(x, radius);
        std::vector<Vec<3>> sorted(x.size());
        for (std::size_t k = 0; k < x.size(); ++k)
            sorted[k] = x[order[k]];
        return sorted;
    };
    const auto fresh_lists = [&](const std::vector<Vec<3>>& positions) {
        SortedGrid<3> fresh;
        NeighbourList list;
        fresh.find(positions, radius, list);
        return std::pair{list, fresh.order()};
    };
    std::vector<std::uint32_t> identity(x.size());
    std::iota(identity.begin(), identity.end(), 0u);
    {
        SortedGrid<3> grid;
        const std::vector<Vec<3>> sorted = permuted(grid);
        NeighbourList list;
        grid.find(sorted, radius, list);
        const auto [expected, expected_order] = fresh_lists(sorted);
        CHECK(grid.order() == identity);
        CHECK(expected_order == identity);
        CHECK(list.start == expected.start);
        CHECK(std::equal(list.index.begin(), list.index.begin() + list.pair_count(),
                         expected.index.begin()));
    }
    {
        // A particle moved across the lattice after the sort.
        SortedGrid<3> grid;
        std::vector<Vec<3>> sorted = permuted(grid);
        sorted[5] += Vec<3>(0.05, 0, 0);
        NeighbourList list;
        grid.find(sorted, radius, list);
        const auto [expected, expected_order] = fresh_lists(sorted);
        CHECK(grid.order() == expected_order);
        CHECK(grid.order() != identity);
        CHECK(as_sorted_rows(list) == as_sorted_rows(expected));
    }
    {
        // One fewer particle, and another radius.
        SortedGrid<3> grid;
        std::vector<Vec<3>> sorted = permuted(grid);
        sorted.pop_back();
        NeighbourList list;
        grid.find(sorted, radius, list);
        CHECK(as_sorted_rows(list) == as_sorted_rows(fresh_lists(sorted).first));
        SortedGrid<3> other;
        const std::vector<Vec<3>> again = permuted(other);
        other.find(again, 1.5 * radius, list);
        SortedGrid<3> wider;
        NeighbourList expected;
        wider.find(again, 1.5 * radius, expected);
        CHECK(as_sorted_rows(list) == as_sorted_rows(expected));
    }
}

TEST_CASE("every neighbour search name makes that search", "[neighbours]") {
    const auto names = neighbour_search_names();
    CHECK(std::find(names.begin(), names.end(), "sorted_grid") != names.end());
    for (const auto& name : names) {
        CHECK(make_neighbour_search<2>(name)->name() == name);
        CHECK(make_neighbour_search<3>(name)->name() == name);
    }
    CHECK_THROWS_AS(make_neighbour_search<3>("octree"), std::invalid_argument);
}

namespace {

// The walls inside `box` by reading every one: what BoundaryParticles::within
// must give.
template <int D>
std::vector<std::uint32_t> walls_inside(std::span<const Vec<D>> walls, const Box<D>& box) {
    std::vector<std::uint32_t> out;
    for (std::size_t b = 0; b < walls.size(); ++b) {
        bool in = true;
        for (int a = 0; a < D; ++a)
            in = in && walls[b][a] >= box.min[a] && walls[b][a] <= box.max[a];
        if (in)
            out.push_back(static_cast<std::uint32_t>(b));
    }
    return out;
}

// The tank of the tests below: 0.8 wide (and deep), 0.5 high.
template <int D>
Box<D> tank() {
    Box<D> domain;
    domain.min = Vec<D>(0);
    domain.max = Vec<D>(0.8);
    domain.max[1] = 0.5;
    return domain;
}

// A tank's walls with a few moving particles after them (a paddle's).
template <int D>
BoundaryParticles<D> tank_walls(const Box<D>& domain, Real spacing, Real h) {
    BoundaryParticles<D> walls = BoundaryParticles<D>::box_walls(domain, spacing, h, 1.0);
    std::vector<Vec<D>> moving = random_cloud<D>(50, 0.2, 0.6, 7);
    walls.add_moving(moving, std::vector<Real>(moving.size(), 1.0),
                     std::vector<std::uint32_t>(moving.size(), 0));
    return walls;
}

template <int D>
void check_within(const BoundaryParticles<D>& walls, const Box<D>& domain) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<Real> at(domain.min[0] - 0.2, domain.max[0] + 0.2);
    std::vector<Box<D>> boxes;
    for (int k = 0; k < 200; ++k) {
        Box<D> box;
        for (int a = 0; a < D; ++a) {
            const Real u = at(rng), v = at(rng);
            box.min[a] = std::min(u, v);
            box.max[a] = std::max(u, v);
        }
        boxes.push_back(box);
    }
    Box<D> whole = domain, empty = domain, flat = domain, nan_box = domain;
    for (int a = 0; a < D; ++a) {
        whole.min[a] -= 1;
        whole.max[a] += 1;
        std::swap(empty.min[a], empty.max[a]);
    }
    // A box one wall site thick: its faces on the sites themselves.
    flat.max[0] = flat.min[0] = walls.positions()[0][0];
    nan_box.min[1] = std::numeric_limits<Real>::quiet_NaN();
    for (const Box<D>& b : {whole, empty, flat, nan_box})
        boxes.push_back(b);
    for (const Box<D>& box : boxes) {
        std::vector<std::uint32_t> got{12345}; // appended to, kept
        walls.within(box, got);
        REQUIRE(!got.empty());
        CHECK(got.front() == 12345);
        got.erase(got.begin());
        CHECK(got == walls_inside<D>(walls.positions(), box));
    }
}

} // namespace

TEMPLATE_TEST_CASE_SIG("walls within a box come from the walls' grid as from reading them all",
                       "[neighbours][walls]", ((int D), D), 2, 3) {
    const Box<D> domain = tank<D>();
    const Real h = 0.045;
    const BoundaryParticles<D> walls = tank_walls<D>(domain, 0.02, h);
    REQUIRE(walls.has_moving());
    check_within(walls, domain);
    // Some of the walls on the whole set's grid (an MPI rank's share).
    std::vector<Vec<D>> some;
    for (std::size_t b = 0; b < walls.moving_begin(); b += 3)
        if (walls.positions()[b][0] < 0.5)
            some.push_back(walls.positions()[b]);
    const BoundaryParticles<D> share(some, std::vector<Real>(some.size(), 1.0), h,
                                     walls.static_bounds());
    check_within(share, domain);
}

TEMPLATE_TEST_CASE_SIG("cell neighbourhoods: the walls' grid gives the same cells as reading "
                       "every wall",
                       "[neighbours][walls]", ((int D), D), 2, 3) {
    const Box<D> domain = tank<D>();
    const Real h = 0.045;
    const BoundaryParticles<D> walls = tank_walls<D>(domain, 0.02, h);
    // Fluid in one corner: most walls are far from it.
    const std::vector<Vec<D>> fluid = random_cloud<D>(D == 2 ? 800 : 3000, 0.01, 0.3, 5);
    CellNeighbourhoods<D> read_all, through_grid;
    read_all.build(fluid, walls.positions(), h, &walls.static_bounds());
    through_grid.build(
        fluid, walls.positions(), h, &walls.static_bounds(),
        [&](const Box<D>& box, std::vector<std::uint32_t>& out) { walls.within(box, out); });
    REQUIRE(read_all.sorted_count() == through_grid.sorted_count());
    REQUIRE(read_all.sorted_count() > fluid.size());
    REQUIRE(read_all.sorted_count() < fluid.size() + walls.size());
    const auto a = read_all.order(), b = through_grid.order();
    CHECK(std::equal(a.begin(), a.end(), b.begin(), b.end()));
    for (std::size_t w = 0; w + fluid.size() < read_all.sorted_count(); ++w)
        CHECK(read_all.wall(w) == through_grid.wall(w));
    REQUIRE(read_all.cell_count() == through_grid.cell_count());
    for (std::size_t c = 0; c < read_all.cell_count(); ++c) {
        const auto x = read_all.cell(c), y = through_grid.cell(c);
        CHECK(x.begin == y.begin);
        CHECK(x.fluid_end == y.fluid_end);
        CHECK(x.candidates == y.candidates);
        CHECK(x.runs.size() == y.runs.size());
    }
}

// The strips a 2D cell pass copies (CellNeighbourhoods::strips): every cell
// with fluid once, row by row and along each row, no strip across two rows
// or two groups of strip_width columns, and the fluid counted before each.
// Dense (a counting sort by row) and with a stray particle far above (rows
// far more than cells: sorted instead).
TEST_CASE("2D strips hold every cell with fluid once, row by row", "[neighbours]") {
    for (const bool stray : {false, true}) {
        std::vector<Vec<2>> fluid = random_cloud<2>(3000, 0, 1, 7);
        if (stray)
            fluid.push_back({0.5, 400.0});
        CellNeighbourhoods<2> cells;
        cells.build(fluid, {}, 0.03);
        std::vector<std::uint32_t> with_fluid;
        for (std::size_t c = 0; c < cells.cell_count(); ++c)
            if (cells.cell(c).has_fluid())
                with_fluid.push_back(static_cast<std::uint32_t>(c));
        const auto strips = cells.strips();
        const auto listed = cells.strip_cells();
        REQUIRE(listed.size() == with_fluid.size());
        REQUIRE(!strips.empty());
        constexpr std::uint32_t width = CellNeighbourhoods<2>::strip_width;
        std::uint32_t next = 0, fluid_before = 0;
        std::vector<std::uint32_t> seen;
        for (std::size_t s = 0; s < strips.size(); ++s) {
            const auto& strip = strips[s];
            CHECK(strip.first == next);
            CHECK(strip.last > strip.first);
            CHECK(strip.fluid_before == fluid_before);
            for (std::uint32_t i = strip.first; i < strip.last; ++i) {
                const auto& cell = listed[i];
                const auto at = cells.coordinates(cell.cell);
                CHECK(cell.x == std::uint32_t(at[0]));
                CHECK(cell.y == std::uint32_t(at[1]));
                CHECK(cell.y == strip.y);
                CHECK(cell.x / width == listed[strip.first].x / width);
                if (i > 0)
                    CHECK((listed[i - 1].y < cell.y ||
                           (listed[i - 1].y == cell.y && listed[i - 1].x < cell.x)));
                fluid_before += cells.cell(cell.cell).fluid_end - cells.cell(cell.cell).begin;
                seen.push_back(cell.cell);
            }
            if (s > 0)
                CHECK((strips[s - 1].y != strip.y ||
                       listed[strips[s - 1].first].x / width != listed[strip.first].x / width));
            next = strip.last;
        }
        CHECK(next == listed.size());
        CHECK(cells.strip_fluid() == fluid.size());
        std::sort(seen.begin(), seen.end());
        CHECK(seen == with_fluid);
    }
}
