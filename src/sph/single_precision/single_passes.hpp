#pragma once
// The single-precision passes (cell_passes.hpp) behind one interface, so that
// their loops can be compiled for several instruction sets in one binary and
// the widest the processor has is picked when the solver is made (issue 22,
// item 2; docs/building.md, "The instruction set").
//
// Each variant is cell_passes.hpp compiled in a translation unit of its own
// (cell_passes_*.cpp) under `#pragma GCC target`, inside a namespace named
// after the variant. Everything that file reads is included here first,
// outside any target region: the inline functions shared with the rest of the
// program (kernels, viscosities, the grid) are then compiled once for the
// build's baseline, and no wider instruction can reach code that runs on
// every processor through the linker's choice between duplicates.

#include "sph/boundaries/boundary_particles.hpp"
#include "sph/headroom.hpp"
#include "sph/kernels.hpp"
#include "sph/neighbours/cell_neighbourhoods.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/params.hpp"
#include "sph/pressure_acceleration.hpp"
#include "sph/state.hpp"

#include <array>
#include <cmath>
#include <cstring>
#include <immintrin.h>
#include <memory>
#include <omp.h>
#include <span>
#include <stdexcept>
#include <string_view>
#include <type_traits>
#include <vector>

namespace sph {

// 2D: the cells made wider than the support by `width` (solver.cell_skin),
// at the fluid's positions `made_at` (the solver keeps them, a step's
// positions, until a particle has moved half the width from its own: the
// cells then still hold every pair within the support, and a cell's
// neighbourhood every candidate; the Verlet skin of molecular dynamics,
// on cells rather than lists). `keep`: the last call's cells were made at
// these same `made_at`, in this memory order, and serve again, with the
// positions refresh_cells last gave. None when `width` is 0.
template <int D>
struct CellSkin {
    std::span<const Vec<D>> made_at;
    Real width = 0; // m
    bool keep = false;
};

template <int D>
class SinglePasses {
  public:
    virtual ~SinglePasses() = default;
    // The grid cells at these positions (fluid and walls): the step's
    // neighbour search. `boundary` may be null. `pair_terms`: the
    // solver.pair_terms the passes will take (params.pair_terms). With a
    // skin (2D, walls that do not move), the cells are made at
    // skin.made_at instead.
    virtual void find_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                            Real radius, PairTerms pair_terms, const CellSkin<D>& skin) = 0;
    // 2D, after find_cells with a skin: the positions the passes read set
    // to these (the same particles), the cells kept; returns the largest
    // squared distance of a particle from where the cells were made at
    // (infinite for one not finite), for the caller to decide whether they
    // still serve.
    virtual Real refresh_cells(std::span<const Vec<D>> fluid) = 0;
    // state.density = sum_j m_j W_ij over fluid and wall particles.
    virtual void density(const Params<D>& params, KernelKind kernel,
                         const BoundaryParticles<D>* boundary, State<D>& state) = 0;
    // state.acceleration = the pressure acceleration with the viscosities
    // the scene names, walls included.
    virtual void pressure_acceleration(const Params<D>& params, KernelKind kernel,
                                       const BoundaryParticles<D>* boundary,
                                       const PairViscosities& viscosities, State<D>& state) = 0;
    // Floats in one of the variant's vector registers: its buffers' padding
    // and its copies' width (a test checks each dispatched variant's).
    virtual std::size_t float_lanes() const = 0;
};

// The variants this binary holds, widest first: "avx512" (x86-64-v4's
// AVX-512 F/VL/BW/DQ with AVX2 and FMA), "avx2" (x86-64-v3: AVX2, FMA),
// "baseline" (the build's -march); a build for the build machine's own
// processor (SPHCLIP_ARCH=native) holds one, "native".
std::span<const std::string_view> simd_variants();
// Whether this processor can run the variant.
bool simd_variant_runs(std::string_view variant);
// The variant the passes use: the environment's SPHCLIP_SIMD when set (tests
// and benchmarks pin a variant with it), else the widest that runs. Throws
// std::runtime_error naming SPHCLIP_SIMD when that names a variant this
// binary lacks or this processor cannot run.
std::string_view simd_variant();

// The widest instructions the chosen variant's loops use: "avx512", "avx2"
// or "sse" (for "native" and "baseline", the build's -march), for the
// benchmarks' headers and run.json.
std::string_view simd_instructions();
// Whether the passes this processor gets (simd_variant()) are at least 8
// floats wide: AVX2 or AVX-512, or a native build for a processor with AVX2.
// solver.precision "auto" chooses single only then. Measured on the flows of
// sphclip_bench_flow (docs/benchmarks.md, "Single precision on each
// processor"): 4 floats wide (SSE, the baseline) the cells' passes run at
// half the speed of the double-precision lists, 8 or 16 wide at 1.5-1.9x.
bool single_passes_pay();

template <int D>
std::unique_ptr<SinglePasses<D>> make_single_passes();

} // namespace sph
