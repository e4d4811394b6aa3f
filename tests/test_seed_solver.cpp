// The seed solver against the seed's formulas (../shared/seed/MODEL.md)
// evaluated by hand for a pair and a triple of particles, in 2D and 3D.
#include "sph/boundaries/boundary_set.hpp"
#include "sph/density.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbours/all_pairs.hpp"
#include "sph/solvers/seed.hpp"

#include <catch2/catch.hpp>
#include <cmath>

using namespace sph;

namespace {

constexpr Real pi = detail::pi;
constexpr Real mu = 0.25; // Pa.s, the viscosity of every case

template <int D>
Params<D> small_params() {
    Params<D> p;
    p.mass = 0.7;
    p.h = 1.0;
    p.rest_density = 2.0;
    p.bulk_modulus = 3.0; // the seed's K' = K / rho0 = 1.5
    p.domain = {Vec<D>(-10), Vec<D>(10)};
    return p;
}

template <int D>
State<D> particles(const std::vector<Vec<D>>& x, const std::vector<Vec<D>>& v) {
    State<D> s;
    s.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        s.position[i] = x[i];
        s.velocity[i] = v[i];
        s.id[i] = static_cast<std::uint32_t>(i);
    }
    return s;
}

template <int D>
void compute_fields(const Params<D>& p, State<D>& s, NeighbourList& list) {
    AllPairs<D>().find(s.position, p.h, list);
    compute_density(p, Poly6<D>(p.h), list, s);
    compute_pressure_linear(p, s);
}

// The seed's force written literally, MODEL.md (2D), with K' = K / rho0.
Vec<2> literal_seed_force_2d(const Params<2>& p, const State<2>& s, int i, int j) {
    const Vec<2> r = s.position[i] - s.position[j];
    const Vec<2> v = s.velocity[i] - s.velocity[j];
    const Real q = glm::length(r) / p.h;
    const Real k = p.bulk_modulus / p.rest_density;
    return p.mass / (pi * std::pow(p.h, 4) * s.density[j]) * (1 - q) *
           (15 * k * (s.density[i] + s.density[j] - 2 * p.rest_density) * (1 - q) / q * r -
            40 * mu * v);
}

// Its 3D counterpart, derived in src/sph/solvers/seed.cpp.
Vec<3> literal_seed_force_3d(const Params<3>& p, const State<3>& s, int i, int j) {
    const Vec<3> r = s.position[i] - s.position[j];
    const Vec<3> v = s.velocity[i] - s.velocity[j];
    const Real q = glm::length(r) / p.h;
    const Real k = p.bulk_modulus / p.rest_density;
    return p.mass / (pi * std::pow(p.h, 5) * s.density[j]) * (1 - q) *
           (22.5 * k * (s.density[i] + s.density[j] - 2 * p.rest_density) * (1 - q) / q * r -
            45 * mu * v);
}

template <int D>
void check_vec(const Vec<D>& got, const Vec<D>& expected) {
    for (int a = 0; a < D; ++a)
        CHECK(got[a] == Approx(expected[a]).epsilon(1e-12).margin(1e-14));
}

} // namespace

TEST_CASE("seed density and force for a pair in 2D, by hand", "[seed]") {
    const auto p = small_params<2>();
    // r = 0.5 = h / 2
    auto s = particles<2>({{0, 0}, {0.3, 0.4}}, {{0.1, 0}, {-0.2, 0.3}});
    NeighbourList list;
    compute_fields(p, s, list);
    // rho = 4 m / (pi h^8) [ (h^2)^3 + (h^2 - r^2)^3 ] = 4 * 0.7 / pi * (1 + 0.75^3)
    CHECK(s.density[0] == Approx(1.2672712343692165).epsilon(1e-14));
    CHECK(s.density[1] == Approx(1.2672712343692165).epsilon(1e-14));
    CHECK(s.pressure[0] == Approx(3.0 * (1.2672712343692165 - 2.0) / 2.0));
    check_vec<2>(seed_pair_force(p, mu, s, 0, 1), literal_seed_force_2d(p, s, 0, 1));
    check_vec<2>(seed_pair_force(p, mu, s, 1, 0), literal_seed_force_2d(p, s, 1, 0));
    // Both below rest density: the pressure term pulls the pair together.
    const Vec<2> push = seed_pair_force(p, mu, s, 0, 1);
    CHECK(glm::dot(push, s.position[0] - s.position[1]) < 0);
}

TEST_CASE("seed interaction for a triple in 2D: a_i = (1/rho_i) sum_j f_ij", "[seed]") {
    auto p = small_params<2>();
    auto s = particles<2>({{0, 0}, {0.3, 0.4}, {-0.2, 0.1}}, {{0.1, 0}, {-0.2, 0.3}, {0, -0.5}});
    NeighbourList list;
    compute_fields(p, s, list);
    // Raise the pressure of one particle so the terms do not cancel.
    s.density[2] = 3.1;
    compute_pressure_linear(p, s);
    compute_seed_interaction(p, mu, list, s);
    for (int i = 0; i < 3; ++i) {
        Vec<2> sum(0);
        for (int j = 0; j < 3; ++j)
            if (j != i)
                sum += literal_seed_force_2d(p, s, i, j);
        check_vec<2>(s.acceleration[i], sum / s.density[i]);
    }
}

TEST_CASE("seed density and interaction for a triple in 3D", "[seed]") {
    auto p = small_params<3>();
    auto s = particles<3>({{0, 0, 0}, {0.3, 0.4, 0.1}, {-0.2, 0.1, 0.3}},
                          {{0.1, 0, 0.2}, {-0.2, 0.3, 0}, {0, -0.5, 0.1}});
    NeighbourList list;
    compute_fields(p, s, list);
    // rho_0 = 315 m / (64 pi h^9) sum_j (h^2 - r^2)^3
    Real sum = 1;
    for (int j = 1; j < 3; ++j)
        sum += std::pow(1 - glm::dot(s.position[j], s.position[j]), 3);
    CHECK(s.density[0] == Approx(315 * 0.7 / (64 * pi) * sum).epsilon(1e-13));
    compute_seed_interaction(p, mu, list, s);
    for (int i = 0; i < 3; ++i) {
        Vec<3> total(0);
        for (int j = 0; j < 3; ++j)
            if (j != i)
                total += literal_seed_force_3d(p, s, i, j);
        check_vec<3>(s.acceleration[i], total / s.density[i]);
    }
}

TEST_CASE("seed pair accelerations are exactly equal and opposite", "[seed]") {
    auto p = small_params<3>();
    auto s = particles<3>({{0, 0, 0}, {0.3, 0.4, 0.1}}, {{0.1, 0, 0.2}, {-0.2, 0.3, 0}});
    NeighbourList list;
    compute_fields(p, s, list);
    s.density[1] = 2.9; // unequal densities: f_ij != -f_ji, but f/rho is symmetric
    compute_pressure_linear(p, s);
    const Vec<3> a01 = seed_pair_acceleration(p, mu, s, 0, 1);
    const Vec<3> a10 = seed_pair_acceleration(p, mu, s, 1, 0);
    CHECK(a01 == -a10);
    CHECK(glm::length(a01) > 0);
}

TEST_CASE("coincident particles get finite, opposite forces", "[seed]") {
    auto p = small_params<2>();
    auto s = particles<2>({{0.5, 0.5}, {0.5, 0.5}, {0.5, 0.5}}, {{0, 0}, {0, 0}, {0, 0}});
    NeighbourList list;
    compute_fields(p, s, list);
    REQUIRE(list.pair_count() == 6);
    p.rest_density = 0.5; // compressed: positive pressure pushes them apart
    compute_pressure_linear(p, s);
    compute_seed_interaction(p, mu, list, s);
    for (int i = 0; i < 3; ++i) {
        CHECK(std::isfinite(s.acceleration[i].x));
        CHECK(std::isfinite(s.acceleration[i].y));
        CHECK(glm::length(s.acceleration[i]) > 0);
    }
    CHECK(seed_pair_acceleration(p, mu, s, 0, 1) == -seed_pair_acceleration(p, mu, s, 1, 0));
    // The same direction every time: the pair's ids choose it.
    CHECK(seed_pair_acceleration(p, mu, s, 0, 1) == seed_pair_acceleration(p, mu, s, 0, 1));
    // Momentum: the pair terms cancel.
    const Vec<2> total = s.acceleration[0] + s.acceleration[1] + s.acceleration[2];
    CHECK(glm::length(total) < 1e-12 * glm::length(s.acceleration[0]));
}

TEST_CASE("the seed solver conserves momentum without walls and gravity", "[seed]") {
    auto p = small_params<2>();
    p.h = 0.1;
    p.mass = 0.01;
    p.rest_density = 1.0;
    p.bulk_modulus = 1.0;
    std::vector<Vec<2>> x, v;
    for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j) {
            x.push_back({0.04 * i + 0.003 * (j % 3), 0.04 * j});
            v.push_back({0.1 * std::sin(i + 2.0 * j), 0.1 * std::cos(3.0 * i - j)});
        }
    auto s = particles<2>(x, v);
    Vec<2> before(0);
    for (auto& vi : s.velocity)
        before += vi;
    AllPairs<2> search;
    NeighbourList list;
    EffectList<2> none;
    NeighbourList no_walls;
    const BoundaryList<2> box = make_boundaries(p);
    StepContext<2> context{search, list, nullptr, no_walls, none, box};
    SeedSolver<2> solver;
    for (int step = 0; step < 200; ++step)
        solver.step(p, 1e-3, s, context);
    Vec<2> after(0);
    Real speed = 0;
    for (auto& vi : s.velocity) {
        after += vi;
        speed += glm::length(vi);
    }
    CHECK(glm::length(after - before) < 1e-12 * speed);
}
