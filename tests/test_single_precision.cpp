// wcsph's single-precision cell passes (src/sph/single_precision/cell_passes.hpp),
// in every instruction-set variant this binary holds and this processor runs,
// against the double passes over neighbour lists, on a flowing state with
// walls and a moving paddle: the same density and accelerations to float's
// round-off, each viscosity's share included; and the scene's
// solver.precision key. (tests/test_simulation.cpp and test_reorder.cpp
// check that 1 and 2 threads give the same bits, in both precisions.)
#include "scene/input_error.hpp"
#include "scene/scene_setup.hpp"
#include "sph/density.hpp"
#include "sph/effects/artificial_viscosity.hpp"
#include "sph/effects/laminar_viscosity.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/pressure_acceleration.hpp"
#include "sph/single_precision/single_passes.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

using namespace sph;

namespace {

// A dam break beside a paddle that pushes into it, far from the origin (the
// cell offsets must keep float's accuracy there), run in double for a while.
template <int D>
Scene flowing_scene(const std::string& kernel, const std::string& precision,
                    const std::string& smoothing_ratio = "null", bool paddle = true) {
    const bool three = D == 3;
    const std::string z = three ? ", 1000.04" : "";
    const std::string z0 = three ? ", 1000" : "";
    if (!paddle)
        return default_scene({
            {"dimension", std::to_string(D)},
            {"solver.name", "wcsph"},
            {"solver.kernel", kernel},
            {"solver.precision", precision},
            {"solver.dt", "2e-4"},
            {"fluid.spacing", "0.005"},
            {"domain.min", "[1000, 1000" + z0 + "]"},
            {"domain.max", "[1000.2, 1000.12" + z + "]"},
            {"fluid.blocks",
             "[{\"min\": [1000, 1000" + z0 + "], \"max\": [1000.08, 1000.08" + z + "]}]"},
        });
    return default_scene({
        {"fluid.smoothing_ratio", smoothing_ratio},
        {"dimension", std::to_string(D)},
        {"solver.name", "wcsph"},
        {"solver.kernel", kernel},
        {"solver.precision", precision},
        {"solver.dt", "2e-4"},
        {"duration", "0.05"},
        {"fluid.spacing", three ? "0.008" : "0.005"},
        {"domain.min", "[1000, 1000" + z0 + "]"},
        {"domain.max", "[1000.2, 1000.12" + z + "]"},
        {"fluid.blocks",
         "[{\"min\": [1000, 1000" + z0 + "], \"max\": [1000.08, 1000.08" + z + "]}]"},
        {"effects.paddles", "[{\"min\": [1000.09, 1000" + z0 + "], \"max\": [1000.11, 1000.1" + z +
                                "], \"motion\": \"linear\", \"velocity\": [-0.5, 0" +
                                (three ? ", 0" : "") + "]}]"},
    });
}

template <int D>
Real largest(const std::vector<Vec<D>>& a) {
    Real m = 0;
    for (const auto& v : a)
        m = std::max(m, glm::length(v));
    return m;
}

template <int D>
Real largest_difference(const std::vector<Vec<D>>& a, const std::vector<Vec<D>>& b) {
    Real m = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        m = std::max(m, glm::length(a[i] - b[i]));
    return m;
}

// SPHCLIP_SIMD set for the scope: the passes made meanwhile are that variant's.
class PinnedVariant {
  public:
    explicit PinnedVariant(std::string_view variant) {
        setenv("SPHCLIP_SIMD", std::string(variant).c_str(), 1);
    }
    ~PinnedVariant() { unsetenv("SPHCLIP_SIMD"); }
};

template <int D>
void check_against_double(const std::string& kernel_name, std::string_view variant,
                          PairTerms pair_terms, const std::string& smoothing_ratio = "null") {
    INFO(D << "D, " << kernel_name << ", variant " << variant << ", pair terms "
           << (pair_terms == PairTerms::once ? "once" : "both sides") << ", smoothing ratio "
           << smoothing_ratio);
    auto sim = make_simulation<D>(flowing_scene<D>(kernel_name, "double", smoothing_ratio));
    for (int k = 0; k < 150; ++k)
        sim.step();
    Params<D> params = sim.params();
    params.pair_terms = pair_terms;
    const BoundaryParticles<D>* walls = sim.boundary();
    REQUIRE(walls != nullptr);
    // The paddle moves: its particles' velocities reach the viscous terms.
    REQUIRE(std::any_of(walls->velocities().begin(), walls->velocities().end(),
                        [](const Vec<D>& v) { return glm::length(v) > 0.1; }));

    const ArtificialViscosity<D> artificial(0.1);
    const LaminarViscosity<D> laminar(0.5); // a syrup: its share is large
    const MonaghanViscosity monaghan = artificial.pair_viscosity(params);
    const MorrisViscosity morris = laminar.pair_viscosity(params);
    const std::vector<PairViscosities> sets{
        {}, {&monaghan, nullptr}, {nullptr, &morris}, {&monaghan, &morris}};

    with_kernel<D>(params.kernel, params.h, [&](const auto& kernel) {
        if constexpr (std::decay_t<decltype(kernel)>::smooth_at_origin) {
            // Double, over neighbour lists.
            State<D> in_double = sim.state();
            NeighbourList neighbours, wall_neighbours;
            SortedGrid<D>().find(in_double.position, params.h, neighbours);
            walls->find_neighbours(in_double.position, wall_neighbours);
            compute_density(params, kernel, neighbours, in_double);
            add_boundary_density(params, kernel, *walls, wall_neighbours, in_double);
            compute_pressure_tait(params, in_double);
            // Single, over cells.
            State<D> in_single = sim.state();
            const PinnedVariant pinned(variant);
            const auto passes = make_single_passes<D>();
            SinglePasses<D>& cells = *passes;
            // Twice, as two steps would: with a wide support the first
            // finds more blocks within reach than the pressure pass's
            // saved lists hold, and the second lists them in wider ones.
            for (int step = 0; step < 2; ++step) {
                cells.find_cells(in_single.position, walls, params.h, params.pair_terms, {});
                cells.density(params, params.kernel, walls, in_single);
            }
            Real worst_density = 0;
            for (std::size_t i = 0; i < in_double.size(); ++i)
                worst_density = std::max(worst_density,
                                         std::abs(in_single.density[i] / in_double.density[i] - 1));
            CHECK(worst_density < 2e-6);
            // The same pressure, so that the accelerations compare the passes only.
            in_single.density = in_double.density;
            in_single.pressure = in_double.pressure;

            std::vector<std::vector<Vec<D>>> doubles, singles;
            std::vector<Real> pressure_term;
            for (const auto& set : sets) {
                compute_pressure_acceleration(params, kernel, neighbours, walls, wall_neighbours,
                                              set, pressure_term, in_double);
                cells.pressure_acceleration(params, params.kernel, walls, set, in_single);
                doubles.push_back(in_double.acceleration);
                singles.push_back(in_single.acceleration);
            }
            const Real scale = largest(doubles[0]);
            REQUIRE(scale > 1);
            CHECK(largest_difference(singles[0], doubles[0]) < 1e-5 * scale);
            // Each viscosity's share (what it adds to the pressure pass)
            // agrees to float's round-off of the whole sum.
            for (std::size_t s = 1; s < sets.size(); ++s) {
                INFO("viscosity set " << s);
                std::vector<Vec<D>> share_double(doubles[s].size()),
                    share_single(doubles[s].size());
                for (std::size_t i = 0; i < share_double.size(); ++i) {
                    share_double[i] = doubles[s][i] - doubles[0][i];
                    share_single[i] = singles[s][i] - singles[0][i];
                }
                const Real share = largest(share_double);
                CHECK(share > 1e-3 * scale); // it does act
                CHECK(largest_difference(share_single, share_double) < 1e-5 * scale + 1e-3 * share);
            }
        }
    });
}

// 2D cells made with a skin at positions up to `moved` (a fraction of the
// skin's width) from the particles' (solver.cell_skin): the same densities
// and accelerations as cells made where the particles are, to float's
// round-off (the candidates come in another order), whether the cells are
// made at those positions or kept from the call before.
void check_skin(std::string_view variant, Real moved) {
    constexpr int D = 2;
    INFO("variant " << variant << ", moved " << moved << " of the skin");
    auto sim = make_simulation<D>(flowing_scene<D>("wendland_c2", "double", "null", false));
    for (int k = 0; k < 150; ++k)
        sim.step();
    const Params<D> params = sim.params();
    const BoundaryParticles<D>* walls = sim.boundary();
    REQUIRE(walls != nullptr);
    REQUIRE(!walls->has_moving());
    const ArtificialViscosity<D> artificial(0.1);
    const MonaghanViscosity monaghan = artificial.pair_viscosity(params);
    const PairViscosities viscosity{&monaghan, nullptr};
    const PinnedVariant pinned(variant);
    // The passes' density, then their accelerations from `reference`'s
    // density and pressure (Tait's from their own density when null), so
    // that two runs' accelerations compare the pressure pass only (Tait's
    // law makes a density's round-off a large pressure's).
    const auto run = [&](SinglePasses<D>& passes, State<D>& state, const CellSkin<D>& skin,
                         const State<D>* reference) {
        passes.find_cells(state.position, walls, params.h, params.pair_terms, skin);
        passes.density(params, params.kernel, walls, state);
        const std::vector<Real> density = state.density;
        if (reference) {
            state.density = reference->density;
            state.pressure = reference->pressure;
        } else
            compute_pressure_tait(params, state);
        passes.pressure_acceleration(params, params.kernel, walls, viscosity, state);
        state.density = density;
    };
    State<D> plain = sim.state();
    run(*make_single_passes<D>(), plain, {}, nullptr);
    // Each particle's cell position a random step from where it is.
    const Real width = 0.2 * params.h;
    std::vector<Vec<D>> made_at = plain.position;
    std::uint64_t seed = 12345;
    const auto uniform = [&seed] { // -1 .. 1
        seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
        return Real(seed >> 11) * 0x1p-52 - 1;
    };
    for (Vec<D>& x : made_at) {
        const Real angle = 3.14159265358979 * uniform(),
                   r = 0.5 * width * moved * std::abs(uniform());
        x += r * Vec<D>(std::cos(angle), std::sin(angle));
    }
    State<D> skinned = sim.state();
    const auto passes = make_single_passes<D>();
    run(*passes, skinned, {made_at, width, false}, &plain);
    const Real scale = largest(plain.acceleration);
    REQUIRE(scale > 1);
    Real worst_density = 0;
    for (std::size_t i = 0; i < plain.size(); ++i)
        worst_density =
            std::max(worst_density, std::abs(skinned.density[i] / plain.density[i] - 1));
    CHECK(worst_density < 1e-6);
    CHECK(largest_difference(skinned.acceleration, plain.acceleration) < 1e-5 * scale);
    // Kept: the particles move on (within the skin) and the cells stay.
    State<D> later = sim.state();
    for (std::size_t i = 0; i < later.size(); ++i)
        later.position[i] += 0.25 * (made_at[i] - later.position[i]);
    State<D> later_plain = later;
    run(*make_single_passes<D>(), later_plain, {}, nullptr);
    Real most = 0;
    for (std::size_t i = 0; i < later.size(); ++i)
        most = std::max(most,
                        glm::dot(later.position[i] - made_at[i], later.position[i] - made_at[i]));
    CHECK(passes->refresh_cells(later.position) == most);
    run(*passes, later, {made_at, width, true}, &later_plain);
    worst_density = 0;
    for (std::size_t i = 0; i < later.size(); ++i)
        worst_density =
            std::max(worst_density, std::abs(later.density[i] / later_plain.density[i] - 1));
    CHECK(worst_density < 1e-6);
    // Against the moved state's own largest acceleration: the random moves
    // bring some pairs closer, and their forces' round-off grows with them.
    const Real later_scale = largest(later_plain.acceleration);
    INFO("largest acceleration " << later_scale << " (" << scale << " before the move)");
    CHECK(largest_difference(later.acceleration, later_plain.acceleration) < 1e-5 * later_scale);
}

} // namespace

TEST_CASE("2D cells with a skin serve particles that moved less than half of it", "[single]") {
    for (const std::string_view variant : simd_variants())
        if (simd_variant_runs(variant))
            check_skin(variant, 0.99);
}

TEST_CASE("single-precision cell passes agree with the double passes", "[single]") {
    int tried = 0;
    for (const std::string_view variant : simd_variants()) {
        if (!simd_variant_runs(variant))
            continue;
        ++tried;
        for (const char* kernel : {"cubic_spline", "wendland_c2"}) {
            check_against_double<2>(kernel, variant, PairTerms::both_sides);
            // 3D: from both sides, and each fluid pair once (the reactions;
            // the walls of the cells before, with the paddle's among them).
            check_against_double<3>(kernel, variant, PairTerms::both_sides);
            check_against_double<3>(kernel, variant, PairTerms::once);
            // A support of about 3.5 spacings (DualSPHysics's 2 sqrt(3)):
            // more blocks within reach than the density pass first saves.
            check_against_double<3>(kernel, variant, PairTerms::once, "3.5");
        }
    }
    CHECK(tried >= 1);
}

TEST_CASE("the widest variant this processor runs is the default; SPHCLIP_SIMD pins one",
          "[single]") {
    const auto variants = simd_variants();
    REQUIRE(!variants.empty());
    // The last is the build's own baseline, which every processor it runs on runs.
    CHECK(simd_variant_runs(variants.back()));
    std::string_view widest;
    for (const auto v : variants)
        if (widest.empty() && simd_variant_runs(v))
            widest = v;
    CHECK(simd_variant() == widest);
    {
        const PinnedVariant pinned(variants.back());
        CHECK(simd_variant() == variants.back());
    }
    {
        const PinnedVariant pinned("avx1024");
        CHECK_THROWS_WITH(simd_variant(), Catch::Contains("SPHCLIP_SIMD=avx1024") &&
                                              Catch::Contains(std::string(variants.back())));
    }
    for (const auto v : variants)
        if (!simd_variant_runs(v)) {
            const PinnedVariant pinned(v);
            CHECK_THROWS_WITH(simd_variant(), Catch::Contains("cannot run"));
        }
}

#if defined(__AVX512F__)
constexpr std::size_t build_float_lanes = 16;
#elif defined(__AVX__)
constexpr std::size_t build_float_lanes = 8;
#else
constexpr std::size_t build_float_lanes = 4;
#endif

TEST_CASE("each dispatched variant runs as wide as its instruction set", "[single]") {
    // GCC's target pragma defines no instruction-set macros: the avx2 and
    // avx512 variants once took the baseline's 4 floats from them.
    for (const std::string_view variant : simd_variants()) {
        if (!simd_variant_runs(variant))
            continue;
        INFO("variant " << variant);
        const PinnedVariant pinned(variant);
        const std::size_t lanes = make_single_passes<3>()->float_lanes();
        if (variant == "avx512")
            CHECK(lanes == 16);
        else if (variant == "avx2")
            CHECK(lanes == 8);
        else // the build's own flags, which this file has too
            CHECK(lanes == build_float_lanes);
    }
}

TEST_CASE("solver.precision: auto picks single where it can run, single says why not", "[single]") {
    // Single where the processor runs the passes 8 floats wide or more.
    for (const std::string_view variant : simd_variants()) {
        if (!simd_variant_runs(variant))
            continue;
        const PinnedVariant pinned(variant);
        INFO("variant " << variant);
        // A portable build's baseline is 4 floats wide (SSE): double there.
        if (variant == "baseline")
            CHECK_FALSE(single_passes_pay());
        if (variant == "avx2" || variant == "avx512")
            CHECK(single_passes_pay());
        CHECK(derive(default_scene({{"solver.name", "wcsph"}})).precision ==
              (single_passes_pay() ? Precision::single : Precision::double_precision));
        // In 3D too, since its passes take each fluid pair once.
        CHECK(derive(default_scene({{"solver.name", "wcsph"}, {"dimension", "3"}})).precision ==
              (single_passes_pay() ? Precision::single : Precision::double_precision));
    }
    // In 3D below 2,000 fluid particles at the start, double (measured
    // faster there).
    {
        const std::vector<Override> few{
            {"solver.name", "wcsph"}, {"dimension", "3"}, {"fluid.spacing", "0.05"}};
        const Derived d = derive(default_scene(few));
        REQUIRE(d.particles < 2000);
        CHECK(d.precision == Precision::double_precision);
        CHECK(to_json(default_scene(few))["solver"]["precision"] == "double");
        REQUIRE(derive(default_scene({{"solver.name", "wcsph"}, {"dimension", "3"}})).particles >=
                2000);
    }
    // Where the single passes cannot run, auto is double in 3D too.
    CHECK(derive(default_scene({{"solver.name", "wcsph"},
                                {"dimension", "3"},
                                {"solver.density_diffusion", "0.1"}}))
              .precision == Precision::double_precision);
    CHECK(
        derive(default_scene(
                   {{"solver.name", "wcsph"}, {"dimension", "3"}, {"solver.precision", "single"}}))
            .precision == Precision::single);
    CHECK(derive(default_scene({{"solver.name", "dfsph"}})).precision ==
          Precision::double_precision);
    CHECK(derive(default_scene({{"solver.name", "seed"}})).precision ==
          Precision::double_precision);
    CHECK(derive(default_scene({{"solver.name", "wcsph"}, {"solver.neighbour_search", "hash"}}))
              .precision == Precision::double_precision);
    CHECK(derive(default_scene({{"solver.name", "wcsph"}, {"effects.xsph.epsilon", "0.5"}}))
              .precision == Precision::double_precision);
    CHECK(derive(default_scene({{"solver.name", "wcsph"}, {"solver.precision", "double"}}))
              .precision == Precision::double_precision);
    for (const std::vector<Override>& bad :
         {std::vector<Override>{{"solver.name", "dfsph"}},
          {{"solver.name", "wcsph"}, {"solver.kernel", "seed"}},
          {{"solver.name", "wcsph"}, {"effects.surface_tension.gamma", "0.1"}},
          {{"solver.name", "wcsph"}, {"solver.neighbour_search", "all_pairs"}}}) {
        std::vector<Override> o = bad;
        o.push_back({"solver.precision", "single"});
        try {
            default_scene(o);
            FAIL("accepted single precision for " << bad.front().value);
        } catch (const InputError& e) {
            CHECK_THAT(e.what(), Catch::Contains("solver.precision"));
        }
    }
}

TEST_CASE("solver.pair_terms: auto takes 3D pairs once from 10,000 particles; once is 3D "
          "single's",
          "[single]") {
    const auto pair_terms = [](const std::vector<Override>& o) {
        return make_params<3>(default_scene(o), derive(default_scene(o))).pair_terms;
    };
    const std::vector<Override> single3{
        {"solver.name", "wcsph"}, {"dimension", "3"}, {"solver.precision", "single"}};
    // The default 3D block at a spacing that gives it fewer than 10,000
    // particles, and at its default spacing (more).
    std::vector<Override> large = single3, small = single3;
    small.push_back({"fluid.spacing", "0.05"});
    const Derived few = derive(default_scene(small)), many = derive(default_scene(large));
    REQUIRE(few.particles < 10000);
    REQUIRE(many.particles >= 10000);
    CHECK(pair_terms(small) == PairTerms::both_sides);
    CHECK(pair_terms(large) == PairTerms::once);
    // run.json's scene records what auto resolved to.
    CHECK(to_json(default_scene(large))["solver"]["pair_terms"] == "once");
    CHECK(to_json(default_scene(small))["solver"]["pair_terms"] == "both_sides");
    // In double precision the pairs are the neighbour lists': both sides.
    std::vector<Override> large_double = large;
    large_double.push_back({"solver.precision", "double"});
    CHECK(pair_terms(large_double) == PairTerms::both_sides);
    std::vector<Override> asked = small;
    asked.push_back({"solver.pair_terms", "once"});
    CHECK(pair_terms(asked) == PairTerms::once);
    large.push_back({"solver.pair_terms", "both_sides"});
    CHECK(pair_terms(large) == PairTerms::both_sides);
    // Refused where the passes take pairs from both sides only.
    for (const std::vector<Override>& bad :
         {std::vector<Override>{{"solver.name", "wcsph"}, {"solver.precision", "single"}},
          {{"solver.name", "wcsph"}, {"dimension", "3"}},
          {{"solver.name", "wcsph"}, {"dimension", "3"}, {"solver.precision", "double"}}}) {
        std::vector<Override> o = bad;
        o.push_back({"solver.pair_terms", "once"});
        try {
            default_scene(o);
            FAIL("accepted solver.pair_terms once");
        } catch (const InputError& e) {
            CHECK_THAT(e.what(), Catch::Contains("solver.pair_terms"));
        }
    }
}
