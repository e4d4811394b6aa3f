// The weakly compressible solver's density and pressure passes in single
// precision, a grid cell at a time: `solver.precision` "single" (docs/solvers.md,
// "Single precision").
//
// Why cells and not neighbour lists: a list costs a gather per pair in each
// pass, and writing it costs more than both passes' arithmetic. Here a cell's
// neighbourhood (the particles of the 3^D cells around it, fluid and wall,
// sph/neighbours/cell_neighbourhoods.hpp) is copied once per pass into
// contiguous float buffers, and every particle of the cell runs one loop over
// all of it, 16 lanes at a time with AVX-512 (8 with AVX2). About a third of
// the candidates are within the support in 2D, a sixth in 3D; the others add
// 0 (the 3D passes skip blocks of them: sum_pairs_once). The same grid
// cells replace the neighbour search.
//
// In 2D the cells go a strip of up to 8 along a row at a time
// (CellNeighbourhoods::strips): the three rows around the strip are copied
// once, a column of three cells after another, so that a cell's 3 x 3
// neighbourhood is one run of the copy and each cell of the rows is copied
// about 3.75 times instead of 9 (before 2026-12-08 each cell copied its
// own 9 cells: the DualSPHysics 5,000-particle dam break is 1.08-1.13x
// faster). A cell's loop runs on past its run's end to a whole vector:
// what lies there is two columns or more away, out of reach, or padding.
//
// In 3D each pair of fluid particles is computed once, by the cell that
// comes first in (z, y, x) order (within a cell, by the particle that comes
// first), which adds the pair's term to its particle and the term's reaction
// to the other's (Newton's third law; for_each_cell): half the pair terms.
// The cells go a tile of 4^3 at a time, and the tile's neighbourhood (6^3
// cells) is copied once, in rows of cells along x, so that a cell's
// candidates are a few runs of it (before 2026-12-07 each cell copied its
// own 14 cells, field by field: 29% of the step). The pressure pass reads
// which blocks of candidates are within reach from the density pass of the
// same step. Taking each pair from both sides, as 2D does, measured at par
// there (docs/benchmarks.md, "The 3D passes a tile at a time").
//
// Accuracy: positions are copied as offsets from a point near them (2D: a
// grid point in the middle of the strip's columns; 3D: the tile's first
// particle), computed in double, so a domain far from the origin loses
// nothing; an offset is at most five cells long in 2D (six in 3D) and keeps
// 24 bits (21 relative to a cell). The per-particle sums
// are taken in float and stored in double. Each particle's sum runs over the
// candidates in the cells' sorted order (in 3D: its own terms in the runs'
// order, then the reactions in the tiles' fixed order), so the result is the
// same with any thread count. The float form of each formula is the double one's
// (kernels, MonaghanViscosity, MorrisViscosity), with the same equations as
// sph/density.hpp and sph/pressure_acceleration.hpp:
//   rho_i = sum_j m_j W_ij, walls included with m_b = rho0 V_b
//   a_i = -sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij) grad W_ij
//         + (2 mu / rho_i) sum_j V_j (x_ij . grad W_ij) / (r^2 + eps) v_ij
// where a wall particle mirrors the fluid particle's pressure and density
// (p_b = p_i, rho_b = rho_i) and has volume V_b, a fluid one V_j = m / rho_j.
// The particle itself is among its candidates: it adds m W(0) to its density
// and, x_ii being 0, nothing to its acceleration. That needs a kernel whose
// gradient is finite at r = 0 (smooth_at_origin: not the seed's spiky one).

// This file is the body of one variant: a translation unit includes it once,
// after single_passes.hpp and inside its `#pragma GCC target` region, with
// SPHCLIP_SIMD_VARIANT naming the variant's namespace (cell_passes_*.cpp).
// It includes nothing itself: a header first read here would be compiled for
// the variant's instructions (single_passes.hpp says why that matters).
#ifndef SPHCLIP_SIMD_VARIANT
#error "cell_passes.hpp is included by the cell_passes_*.cpp variants only"
#endif
#include "sph/single_precision/single_passes.hpp"
#include "sph/thread_runs.hpp"

namespace sph::SPHCLIP_SIMD_VARIANT {

// The variant's vector registers, in bits: named by a dispatched variant's
// file (SPHCLIP_SIMD_BITS), since GCC 12's target pragma does not define the
// instruction sets' macros for what it enables (the variants ran 4 floats
// a register in their padding and copies until 2026-12-06); else from the
// build's own flags.
#ifndef SPHCLIP_SIMD_BITS
#if defined(__AVX512F__)
#define SPHCLIP_SIMD_BITS 512
#elif defined(__AVX__)
#define SPHCLIP_SIMD_BITS 256
#else
#define SPHCLIP_SIMD_BITS 128
#endif
#endif
// Floats in one vector register of the variant: the cell loops' width.
inline constexpr std::uint32_t float_lanes = SPHCLIP_SIMD_BITS / 32;
static_assert(float_lanes <= SortedGrid<2>::sorted_tail);
// Candidates the 3D passes skip at once when none is within the support
// (CellPasses::sum_pairs_once): 8 was faster than 16 on the 3D
// dam break (a model of particles at random in their cells has 57% of the
// blocks of 8 out of reach, 45% of those of 16). A divisor of the buffers'
// padding, float_lanes.
inline constexpr std::size_t skip_block = float_lanes < 8 ? float_lanes : 8;
static_assert(float_lanes % skip_block == 0);

template <int D>
class CellPasses {
  public:
    // The cells at these positions (fluid and walls): the step's neighbour
    // search. `boundary` may be null. 3D passes that take each pair once
    // read the tiles' neighbourhoods, not each cell's runs.
    void find_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                    Real radius, PairTerms pair_terms, const CellSkin<D>& skin) {
        // 2D reads strips(), 3D each pair once its tiles'.
        const bool cell_runs = D == 3 && pair_terms != PairTerms::once;
        near_saved_ = false;
        halos_saved_ = false;
        if (D == 2 && skin.width > 0) {
            // On the DualSPHysics 2D dam break (5,000 particles) the cells'
            // build was 17% of the step (docs/benchmarks.md).
            if (boundary && boundary->has_moving())
                throw std::logic_error("cells with a skin need walls that stay");
            if (!skin.keep) {
                make_cells(skin.made_at, boundary, radius + skin.width, cell_runs);
                cells_.refresh_fluid_positions(fluid);
            }
            return;
        }
        make_cells(fluid, boundary, radius, cell_runs);
    }
    Real refresh_cells(std::span<const Vec<D>> fluid) {
        return cells_.refresh_fluid_positions(fluid);
    }

  private:
    void make_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                    Real radius, bool cell_runs) {
        if (boundary)
            cells_.build(
                fluid, boundary->positions(), radius, &boundary->static_bounds(),
                [boundary](const Box<D>& box, std::vector<std::uint32_t>& out) {
                    boundary->within(box, out);
                },
                cell_runs, !boundary->has_moving());
        else
            cells_.build(fluid, {}, radius, nullptr, {}, cell_runs);
    }

  public:
    // state.density = sum_j m_j W_ij over fluid and wall particles.
    template <class Kernel>
    void density(const Params<D>& params, const Kernel& double_kernel,
                 const BoundaryParticles<D>* boundary, State<D>& state) {
        const typename Kernel::Single kernel(double_kernel.h);
        const auto order = cells_.order();
        const std::size_t n = cells_.fluid_count(), total = cells_.sorted_count();
        resize_with_headroom(sorted_.mass, total + float_lanes);
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < total; ++k) {
            const std::uint32_t j = order[k];
            sorted_.mass[k] =
                float(j < n ? params.mass
                            : params.rest_density * boundary->volumes()[cells_.wall(j - n)]);
        }
        // In 3D a fluid pair's term is the same for both particles (equal
        // masses), so the candidate's reaction is +1 times it.
        const bool once = D == 3 && params.pair_terms == PairTerms::once;
        const auto fields = [&](Buffers& b, const auto& copy) {
            copy(sorted_.mass, b.mass, 0.f);
        };
        if (once) {
            near_slot_size_ = next_near_slot_size_;
            resize_with_headroom(near_blocks_, total * near_slot_size_);
        }
        for_each_cell(
            once ? 1 : 0, fields, [&](const Cell& cell, Buffers& b, const Vec<D>& reference) {
                const Lanes l = b.lanes();
                for (std::uint32_t k = cell.begin; k < cell.fluid_end; ++k) {
                    const FVec x_i = offset(k, reference);
                    // The kernel's constant times the sum, not each term.
                    const auto term = [=](std::size_t m) {
                        const FVec x_ij = x_i - l.position(m);
                        const float r2 = glm::dot(x_ij, x_ij);
                        return l.mass[m] * kernel.W_shape(std::sqrt(r2));
                    };
                    if constexpr (D == 2)
                        state.density[order[k]] =
                            kernel.W_scale() * sum_candidates<float>(l.padded, term);
                    else if (!once)
                        state.density[order[k]] =
                            kernel.W_scale() *
                            sum_pairs_once<float, 0>(l, k, x_i, kernel.h, term, {});
                    else {
                        sums_[0][k] +=
                            sum_pairs_once<float, 1>(l, k, x_i, kernel.h, term, b.reactions(),
                                                     {near_slot(k), near_slot_size_, true, false});
                        b.unsaved += near_slot(k)[0] == NearBlocks::unsaved ? 1 : 0;
                    }
                }
            });
        if (once) {
            // Wider slots for the next step when more than 1% of the
            // particles had more blocks within reach than a slot holds (a
            // kernel's support of 3.5 spacings has about 25).
            std::size_t unsaved = 0;
            for (Buffers& b : buffers_) {
                unsaved += b.unsaved;
                b.unsaved = 0;
            }
            if (unsaved * 100 > n && near_slot_size_ < NearBlocks::largest_slot)
                next_near_slot_size_ = 2 * near_slot_size_;
            finish([&](std::uint32_t k, const FVec& sum) {
                state.density[order[k]] = kernel.W_scale() * sum[0];
            });
            near_saved_ = true;
            near_support_ = kernel.h;
        }
    }

    // state.acceleration = the pressure acceleration with the viscosities
    // the scene names, walls included.
    template <class Kernel>
    void pressure_acceleration(const Params<D>& params, const Kernel& double_kernel,
                               const BoundaryParticles<D>* boundary,
                               const PairViscosities& viscosities, State<D>& state) {
        static_assert(Kernel::smooth_at_origin, "a particle is its own candidate");
        const typename Kernel::Single kernel(double_kernel.h);
        const auto order = cells_.order();
        const std::size_t n = cells_.fluid_count(), total = cells_.sorted_count();
        for (int a = 0; a < D; ++a)
            resize_with_headroom(sorted_.velocity[a], total + float_lanes);
        for (auto* field : {&sorted_.mass, &sorted_.density, &sorted_.pressure_term,
                            &sorted_.volume, &sorted_.own_weight})
            resize_with_headroom(*field, total + float_lanes);
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < total; ++k) {
            const std::uint32_t j = order[k];
            const bool fluid = j < n;
            const Vec<D> v = fluid ? state.velocity[j] : boundary->velocities()[cells_.wall(j - n)];
            for (int a = 0; a < D; ++a)
                sorted_.velocity[a][k] = float(v[a]);
            if (fluid) {
                const Real rho = state.density[j];
                sorted_.mass[k] = float(params.mass);
                sorted_.density[k] = float(rho);
                sorted_.pressure_term[k] = float(state.pressure[j] / (rho * rho));
                sorted_.volume[k] = float(params.mass / rho);
                sorted_.own_weight[k] = 1;
            } else {
                const Real volume = boundary->volumes()[cells_.wall(j - n)];
                sorted_.mass[k] = float(params.rest_density * volume);
                sorted_.density[k] = 0; // the fluid particle's, in the loop
                sorted_.pressure_term[k] = 0;
                sorted_.volume[k] = float(volume);
                sorted_.own_weight[k] = 2;
            }
        }
        const bool once = D == 3 && params.pair_terms == PairTerms::once;
        const bool near_saved = once && near_saved_ && near_support_ == kernel.h;
        const bool hydrostatic_walls = params.wall_gravity != Vec<D>(0);
        const FVec wall_gravity(params.wall_gravity);
        const float scale = -kernel.dW_over_r_scale();
        // Compiled for each set of viscosities (PairViscosities::dispatch) and
        // wall pressure: a test in the loop would keep it from vectorising
        // (measured: the whole run 3x slower).
        const auto accelerate = [&](auto artificial_flag, auto laminar_flag,
                                    auto hydrostatic_flag) {
            constexpr bool artificial = decltype(artificial_flag)::value;
            constexpr bool laminar = decltype(laminar_flag)::value;
            constexpr bool hydrostatic = decltype(hydrostatic_flag)::value;
            const MonaghanTerm<float> Pi =
                artificial ? viscosities.artificial->single() : MonaghanTerm<float>{};
            const MorrisViscosity::Single morris =
                laminar ? viscosities.laminar->single() : MorrisViscosity::Single{};
            const auto fields = [&](Buffers& b, const auto& copy) {
                for (int a = 0; a < D; ++a)
                    copy(sorted_.velocity[a], b.velocity[a], 0.f);
                copy(sorted_.mass, b.mass, 0.f);
                copy(sorted_.pressure_term, b.pressure_term, 0.f);
                copy(sorted_.own_weight, b.own_weight, 0.f);
                if constexpr (artificial)
                    copy(sorted_.density, b.density, 1.f);
                if constexpr (laminar)
                    copy(sorted_.volume, b.volume, 0.f);
            };
            for_each_cell(
                once ? D : 0, fields, [&](const Cell& cell, Buffers& b, const Vec<D>& reference) {
                    const Lanes l = b.lanes();
                    for (std::uint32_t k = cell.begin; k < cell.fluid_end; ++k) {
                        const FVec x_i = offset(k, reference);
                        FVec v_i;
                        for (int a = 0; a < D; ++a)
                            v_i[a] = sorted_.velocity[a][k];
                        const float pt_i = sorted_.pressure_term[k], rho_i = sorted_.density[k];
                        [[maybe_unused]] const float inverse_rho_i = 1.f / rho_i;
                        const float viscous_scale = laminar ? morris.two_mu / rho_i : 0.f;
                        const auto term = [=](std::size_t m) {
                            const FVec x_ij = x_i - l.position(m);
                            const FVec v_ij = v_i - l.velocity(m);
                            const float r2 = glm::dot(x_ij, x_ij);
                            const float v_dot_x = glm::dot(v_ij, x_ij);
                            const float r = std::sqrt(r2);
                            // The kernel's constant, -1 times, multiplies the
                            // sum, not each term (all are linear in it).
                            const float g = kernel.dW_over_r_shape(r);
                            // A wall's pressure term and density are stored as 0
                            // and its own_weight as 2 (a fluid particle's 1), so
                            // these sums are exactly the fluid pair's or twice
                            // particle i's (p_b = p_i, rho_b = rho_i), each one
                            // product and sum, rounded once. Not a select: GCC made
                            // the load under one a masked load, and then kept the
                            // loop's two sums in memory, a store and a load in the
                            // critical path of every vector of candidates.
                            const float own = l.own_weight[m];
                            float factor;
                            if constexpr (hydrostatic) {
                                // (p_i + p_b) / rho_i^2 with the wall's hydrostatic
                                // rise, p_b = max(p_i + rho_i g . (x_b - x_i), 0).
                                const float p_b = std::max(
                                    pt_i - glm::dot(wall_gravity, x_ij) * inverse_rho_i, 0.f);
                                factor = pt_i + (l.pressure_term[m] + (own - 1) * p_b);
                            } else
                                factor = own * pt_i + l.pressure_term[m];
                            if constexpr (artificial)
                                factor += Pi(v_dot_x, own * rho_i + l.density[m], r2);
                            const float pressure = l.mass[m] * factor * g;
                            // Without the laminar term no `- 0 * v_ij`: GCC keeps
                            // it (v_ij may be infinite), 2 operations a vector.
                            if constexpr (!laminar)
                                return pressure * x_ij;
                            else
                                return pressure * x_ij -
                                       viscous_scale * morris(l.volume[m], r2 * g, r2) * v_ij;
                        };
                        // Between fluid particles the term is antisymmetric (the
                        // same mass; p_i/rho_i^2 + p_j/rho_j^2, Pi_ij and the
                        // laminar 2 mu m / (rho_i rho_j) symmetric in i and j), so
                        // the candidate's reaction is -1 times it.
                        if constexpr (D == 2)
                            state.acceleration[order[k]] =
                                Vec<D>(scale * sum_candidates<FVec>(l.padded, term));
                        else if (!once)
                            state.acceleration[order[k]] = Vec<D>(
                                scale * sum_pairs_once<FVec, 0>(l, k, x_i, kernel.h, term, {}));
                        else {
                            const FVec a_i = sum_pairs_once<FVec, -1>(
                                l, k, x_i, kernel.h, term, b.reactions(),
                                {near_slot(k), near_slot_size_, false, near_saved});
                            for (int a = 0; a < D; ++a)
                                sums_[a][k] += a_i[a];
                        }
                    }
                });
            if (once)
                finish([&](std::uint32_t k, const FVec& sum) {
                    state.acceleration[order[k]] = Vec<D>(scale * sum);
                });
        };
        viscosities.dispatch([&](auto artificial, auto laminar) {
            if (hydrostatic_walls)
                accelerate(artificial, laminar, std::true_type{});
            else
                accelerate(artificial, laminar, std::false_type{});
        });
    }

  private:
    using FVec = glm::vec<D, float>;
    // Per sorted entry, in float.
    struct SortedFields {
        std::array<std::vector<float>, D> velocity;
        std::vector<float> mass, density, pressure_term, volume, own_weight;
    };
    // 3D: a run of candidates in a thread's buffers, [begin, end), or,
    // `after_own`, [the particle's own entry + 1, end). Those with
    // `reaction` get the terms' reactions. A block of skip_block may read
    // past `end`: what lies there is out of reach (a cell two or more along
    // x) or padding, so its terms are 0.
    struct Run {
        std::uint32_t begin, end;
        bool after_own, reaction;
    };
    static constexpr int max_runs = 16;
    // A cell's neighbourhood as the loops read it: plain pointers, copied
    // into each loop's closure, so GCC sees that no load changes in the loop
    // (through a reference to the vectors it keeps the loop scalar).
    struct Lanes {
        const float *x, *y, *z, *vx, *vy, *vz; // z, vz: 3D only
        const float *mass, *density, *pressure_term, *volume, *own_weight;
        std::size_t padded;
        std::uint32_t* near_blocks; // scratch: a block index per block of the runs
        const Run* runs;            // 3D: those without reaction first
        int run_count;
        // 3D, a tile at a time: the buffer entry of sorted entry k of the
        // cell, own_at + (k - own_begin).
        std::uint32_t own_at, own_begin;

        FVec position(std::size_t m) const {
            if constexpr (D == 2)
                return {x[m], y[m]};
            else
                return {x[m], y[m], z[m]};
        }
        FVec velocity(std::size_t m) const {
            if constexpr (D == 2)
                return {vx[m], vy[m]};
            else
                return {vx[m], vy[m], vz[m]};
        }
    };
    using HaloCell = typename CellNeighbourhoods<D>::HaloCell;
    static constexpr int halo_width = CellNeighbourhoods<D>::halo_width;
    static constexpr int halo_cells = CellNeighbourhoods<D>::halo_cells;
    // One thread's copy of a cell's neighbourhood (2D, and 3D with
    // solver.pair_terms "both") or of a tile's (3D, each pair once), padded
    // to whole vectors. A cache line of its own: a thread writes `padded`
    // for every cell, and sharing its line with the next thread's vectors
    // cost 2D a third of the second thread's gain.
    struct alignas(64) Buffers {
        std::array<std::vector<float>, D> x, velocity;
        std::vector<float> mass, density, pressure_term, volume, own_weight;
        std::vector<std::uint32_t> near_blocks;
        // 3D, a tile at a time: the terms the tile's particles gave each
        // fluid candidate (reaction[0] alone for the density).
        std::array<std::vector<float>, D> reaction;
        std::size_t padded = 0;
        std::size_t size = 0; // of each vector above but near_blocks
        // 3D: the tile's neighbourhood (CellNeighbourhoods::tile_halo), where
        // each cell's fluid and walls lie in the buffers, the cell's runs.
        std::array<HaloCell, halo_cells> halo;
        std::array<std::uint32_t, halo_cells> fluid_at, wall_at;
        // The runs of sorted entries copied there, and where a row's
        // padding goes.
        struct Piece {
            std::uint32_t begin, end, at;
        };
        std::vector<Piece> pieces;
        std::vector<std::uint32_t> pads;
        std::array<Run, max_runs> runs;
        int run_count = 0;
        std::size_t unsaved = 0; // particles whose NearBlocks did not fit
        std::uint32_t own_at = 0, own_begin = 0;
        // 2D: the cell's candidates start here in the buffers (its strip's
        // copy), and where each column of the strip's copy starts.
        std::size_t at = 0;
        std::array<std::uint32_t, CellNeighbourhoods<D>::strip_width + 3> column_at{};

        Lanes lanes() {
            return {x[0].data() + at,
                    x[1].data() + at,
                    D == 3 ? x[D - 1].data() : nullptr,
                    velocity[0].data() + at,
                    velocity[1].data() + at,
                    D == 3 ? velocity[D - 1].data() : nullptr,
                    mass.data() + at,
                    density.data() + at,
                    pressure_term.data() + at,
                    volume.data() + at,
                    own_weight.data() + at,
                    padded,
                    near_blocks.data(),
                    runs.data(),
                    run_count,
                    own_at,
                    own_begin};
        }
        std::array<float*, D> reactions() {
            std::array<float*, D> r;
            for (int a = 0; a < D; ++a)
                r[a] = reaction[a].data();
            return r;
        }
        // Room for `entries` candidates, a vector past them and a block
        // index for each block of up to max_runs runs over them.
        void reserve(std::size_t entries) {
            if (entries + float_lanes <= size)
                return;
            size = entries + float_lanes;
            for (int a = 0; a < D; ++a) {
                resize_with_headroom(x[a], size);
                resize_with_headroom(velocity[a], size);
                if constexpr (D == 3)
                    resize_with_headroom(reaction[a], size);
            }
            for (auto* field : {&mass, &density, &pressure_term, &volume, &own_weight})
                resize_with_headroom(*field, size);
            resize_with_headroom(near_blocks, size / skip_block + max_runs + 1);
        }
    };

    using Cell = typename CellNeighbourhoods<D>::Cell;
    using Range = typename CellNeighbourhoods<D>::Range;

    // Calls work(cell, buffers, reference) for every cell holding fluid, in
    // parallel, with this thread's buffers holding the cell's candidates'
    // positions as offsets from `reference` and the fields that
    // fields(buffers, copy) names by calling copy(sorted field, buffer
    // field, padding) for each.
    // 2D: a strip of cells at a time (copy_strip), the cell's candidates
    // b.lanes() from b.at.
    // 3D: each fluid pair in two different cells is taken once (Newton's
    // third law), by the cell first in (z, y, x) order: its particles run
    // over the walls of the 27 cells around it and its own particles without
    // reaction, and over the fluid of the 13 cells after it, writing the
    // terms they give those particles to b.reaction (`parts` floats a
    // candidate). A tile of cells at a time: its neighbourhood, 6^3 cells, is
    // copied into the buffers once, fluid and walls apart, a row of cells
    // along x after another, so that a cell's candidates are 15 runs at most
    // (lay_out_tile); when the tile is done, its reactions are added into
    // sums_. The tiles go colour by colour, so no two threads add into one
    // particle's sums at once, and each sum's order of additions is the same
    // with any thread count. work adds each particle's own sum into sums_;
    // finish then hands the sums over. Before 2026-12-07 each cell copied
    // its own neighbourhood, 14 cells, field by field: 29% of the 3D step.
    template <class Fields, class Work>
    void for_each_cell(int parts, const Fields& fields, const Work& work) {
        if constexpr (D == 2) {
            prepare_buffers();
            const auto strips = cells_.strips();
            const auto strip_cells = cells_.strip_cells();
            // Each thread one run of consecutive strips, the runs of about
            // as many particles (sph/thread_runs.hpp).
#pragma omp parallel
            {
                Buffers& b = buffers_[omp_get_thread_num()];
                for (const std::size_t s :
                     this_thread_run(strips.size(), cells_.strip_fluid(),
                                     [&](std::size_t k) { return strips[k].fluid_before; })) {
                    const auto& strip = strips[s];
                    const Vec<D> reference = copy_strip(strip, b, fields);
                    const std::uint32_t first_x = strip_cells[strip.first].x;
                    for (std::uint32_t i = strip.first; i < strip.last; ++i) {
                        // Columns x - 1 .. x + 1: those after may follow in
                        // the padded run, all out of reach.
                        const std::uint32_t column = strip_cells[i].x - first_x;
                        b.at = b.column_at[column];
                        b.padded = (b.column_at[column + 3] - b.at + float_lanes - 1) /
                                   float_lanes * float_lanes;
                        work(cells_.cell(strip_cells[i].cell), b, reference);
                    }
                    b.at = 0;
                }
            }
        } else if (parts == 0) {
            prepare_buffers();
            const std::size_t count = cells_.cell_count();
            const std::size_t particles = cells_.sorted_count();
            // Each thread one run of consecutive cells, the runs of about
            // as many particles (sph/thread_runs.hpp), rather than cells
            // dealt out 16 at a time.
#pragma omp parallel
            {
                Buffers& b = buffers_[omp_get_thread_num()];
                for (const std::size_t c : this_thread_run(
                         count, particles, [&](std::size_t k) { return cells_.cell(k).begin; })) {
                    const Cell cell = cells_.cell(c);
                    if (!cell.has_fluid())
                        continue;
                    const Vec<D> reference = gather_positions(cell, b);
                    fields(b, [&](const std::vector<float>& field, std::vector<float>& out,
                                  float padding) { gather(cell, field, out, padding); });
                    b.runs[0] = {0, static_cast<std::uint32_t>(b.padded), false, false};
                    b.run_count = 1;
                    work(cell, b, reference);
                }
            }
        } else if constexpr (D == 3) {
            buffers_.resize(std::max<std::size_t>(buffers_.size(), omp_get_max_threads()));
            cells_.tile_cells();
            // The tiles' neighbourhoods as the pass before found them, on
            // the same cells (the pressure pass after the density one).
            const bool reuse_halos = halos_saved_;
            if (!reuse_halos)
                resize_with_headroom(halos_, cells_.tiles());
            const std::size_t total = cells_.sorted_count();
            for (int a = 0; a < D; ++a)
                resize_with_headroom(sums_[a], total);
#pragma omp parallel
            {
#pragma omp for schedule(static)
                for (std::size_t k = 0; k < total; ++k)
                    for (int a = 0; a < parts; ++a)
                        sums_[a][k] = 0;
                Buffers& b = buffers_[omp_get_thread_num()];
                const auto cells = cells_.tiled_cells();
                for (int q = 0; q < CellNeighbourhoods<D>::colours; ++q) {
#pragma omp for schedule(dynamic, 1)
                    for (std::size_t t = 0; t < cells_.tile_count(q); ++t) {
                        const std::uint32_t first = cells_.tile_start(q, t),
                                            last = cells_.tile_start(q, t + 1);
                        const Cell first_cell = cells_.cell(cells[first]);
                        TileHalo& saved = halos_[cells_.tile_index(q, t)];
                        if (reuse_halos)
                            b.halo = saved.halo;
                        else {
                            saved.corner = cells_.tile_halo(cells[first], b.halo);
                            saved.halo = b.halo;
                        }
                        const auto corner = saved.corner;
                        const std::uint32_t fluid_entries = lay_out_tile(b);
                        const Vec<D> reference = offset_reference(first_cell.begin);
                        copy_tile(b, reference, fields);
                        for (int a = 0; a < parts; ++a)
                            std::fill(b.reaction[a].data(), b.reaction[a].data() + fluid_entries,
                                      0.f);
                        for (std::uint32_t i = first; i < last; ++i) {
                            const std::size_t c = cells[i];
                            const auto at = cells_.coordinates(c);
                            cell_runs(b, int(at[0] - corner[0]), int(at[1] - corner[1]),
                                      int(at[2] - corner[2]));
                            work(cells_.cell(c), b, reference);
                        }
                        for (int h = 0; h < halo_cells; ++h) {
                            const HaloCell& cell = b.halo[h];
                            for (int a = 0; a < parts; ++a) {
                                float* const to = sums_[a].data() + cell.begin;
                                const float* const from = b.reaction[a].data() + b.fluid_at[h];
#pragma omp simd
                                for (std::uint32_t m = 0; m < cell.fluid_end - cell.begin; ++m)
                                    to[m] += from[m];
                            }
                        }
                    }
                }
            }
            halos_saved_ = true;
        }
    }
    // 3D, after for_each_cell: finish(k, sum) for every fluid particle's
    // sorted entry k.
    template <class Finish>
    void finish(const Finish& finish_one) const {
        const auto order = cells_.order();
        const std::size_t total = cells_.sorted_count(), n = cells_.fluid_count();
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < total; ++k) {
            if (order[k] >= n)
                continue;
            FVec sum;
            for (int a = 0; a < D; ++a)
                sum[a] = sums_[a][k];
            finish_one(static_cast<std::uint32_t>(k), sum);
        }
    }

    void prepare_buffers() {
        buffers_.resize(std::max<std::size_t>(buffers_.size(), omp_get_max_threads()));
        // Each segment's padding, and a vector past the end.
        const std::size_t size = cells_.max_candidates() + 3 * skip_block + 2 * float_lanes;
        for (Buffers& b : buffers_)
            b.reserve(size);
    }

    // 2D: copies the three rows of cells around the strip into b, a column
    // after another from the one before its first cell to the one after its
    // last, each column's cells from the row below up (fluid and walls);
    // b.column_at[i] is where column first - 1 + i starts, the last entry
    // where the copy ends, and a vector of padding follows. The positions
    // are offsets from the returned reference, a point fixed on the grid
    // for the strip's columns: the middle of the strip_width columns that
    // hold it, half a cell up its row, at most strip_width / 2 + 1 cells
    // from any candidate along x (in float, x_ij then errs by 6e-7 of a
    // cell at most).
    template <class Fields>
    [[gnu::noinline]] Vec<D> copy_strip(const typename CellNeighbourhoods<D>::Strip& strip,
                                        Buffers& b, const Fields& fields) const {
        constexpr std::uint32_t width = CellNeighbourhoods<D>::strip_width;
        const auto cells = cells_.strip_cells();
        const std::int64_t first = cells[strip.first].x, last = cells[strip.last - 1].x;
        b.pieces.clear();
        std::uint32_t at = 0;
        int column = 0;
        for (std::int64_t x = first - 1; x <= last + 1; ++x, ++column) {
            b.column_at[column] = at;
            for (std::int64_t y = std::int64_t(strip.y) - 1; y <= std::int64_t(strip.y) + 1; ++y) {
                const Range r = cells_.range_at({x, y});
                if (r.end > r.begin) {
                    b.pieces.push_back({r.begin, r.end, at});
                    at += r.end - r.begin;
                }
            }
        }
        b.column_at[column] = at;
        b.reserve(at);
        const Vec<D> reference =
            cells_.grid_point({Real(first / width * width + width / 2), Real(strip.y) + Real(0.5)});
        // Whole vectors past each piece's end, as gather_positions does: the
        // next piece, or the padding, written after, overwrites them.
        for (int a = 0; a < D; ++a) {
            const PositionCopy copy{cells_.sorted_positions(a).data(), b.x[a].data(), reference[a]};
            for (const auto& piece : b.pieces)
                copy(piece.begin, piece.end, piece.at);
            fill_lanes(b.x[a].data() + at, 1e18f);
        }
        fields(b, [&](const std::vector<float>& field, std::vector<float>& out, float padding) {
            const FieldCopy copy{field.data(), out.data(), padding};
            for (const auto& piece : b.pieces)
                copy(piece.begin, piece.end, piece.at);
            fill_lanes(out.data() + at, padding);
        });
        return reference;
    }

    // 3D: where the tile's neighbourhood goes in b: the fluid of its cells a
    // row along x after another, then their walls so, each row that holds
    // any followed by a block of padding (a block that reads past a row's
    // end reads that).
    // Returns where the walls start. Not inlined, nor are copy_tile and
    // cell_runs: inlined into for_each_cell, they made GCC stop inlining the
    // kernel into the pair loops, which then ran scalar (the pressure pass
    // 600 against 120 ns a particle-step).
    [[gnu::noinline]] std::uint32_t lay_out_tile(Buffers& b) const {
        b.pieces.clear();
        b.pads.clear();
        std::uint32_t at = 0, row = 0;
        const auto lay_out = [&](int h, std::uint32_t begin, std::uint32_t end) {
            if (end > begin)
                b.pieces.push_back({begin, end, at});
            at += end - begin;
            if ((h + 1) % halo_width == 0 && at > row) {
                b.pads.push_back(at);
                at += skip_block;
                row = at;
            }
        };
        for (int h = 0; h < halo_cells; ++h) {
            b.fluid_at[h] = at;
            lay_out(h, b.halo[h].begin, b.halo[h].fluid_end);
        }
        const std::uint32_t fluid_entries = at;
        for (int h = 0; h < halo_cells; ++h) {
            b.wall_at[h] = at;
            lay_out(h, b.halo[h].fluid_end, b.halo[h].end);
        }
        b.reserve(at);
        b.padded = at;
        return fluid_entries;
    }
    // 3D: copies the tile's neighbourhood into b as lay_out_tile placed it,
    // the positions as offsets from `reference`.
    template <class Fields>
    [[gnu::noinline]] void copy_tile(Buffers& b, const Vec<D>& reference,
                                     const Fields& fields) const {
        // Whole vectors past each cell's end, as gather_positions does: the
        // next cell, or the row's padding, written after, overwrites them.
        const auto each_piece = [&](const auto& copy) {
            for (const auto& piece : b.pieces)
                copy(piece.begin, piece.end, piece.at);
            for (const std::uint32_t at : b.pads)
                copy.pad(at);
        };
        for (int a = 0; a < D; ++a)
            each_piece(
                PositionCopy{cells_.sorted_positions(a).data(), b.x[a].data(), reference[a]});
        fields(b, [&](const std::vector<float>& field, std::vector<float>& out, float padding) {
            each_piece(FieldCopy{field.data(), out.data(), padding});
        });
    }
    // Copies of runs of sorted entries into a buffer, a vector at a time
    // (past the run's end), and a block of padding.
    struct PositionCopy {
        const Real* from;
        float* to;
        Real reference;
        void operator()(std::uint32_t begin, std::uint32_t end, std::size_t at) const {
            const Real* source = from + begin;
            float* target = to + at;
            const std::size_t length = end - begin;
            for (std::size_t c = 0; c < length; c += float_lanes)
                for (std::size_t l = 0; l < float_lanes; ++l)
                    target[c + l] = float(source[c + l] - reference);
        }
        void pad(std::size_t at) const {
            for (std::size_t l = 0; l < skip_block; ++l)
                to[at + l] = 1e18f;
        }
    };
    struct FieldCopy {
        const float* from;
        float* to;
        float padding;
        void operator()(std::uint32_t begin, std::uint32_t end, std::size_t at) const {
            for (std::uint32_t c = 0; c < end - begin; c += float_lanes)
                std::memcpy(to + at + c, from + begin + c, float_lanes * sizeof(float));
        }
        void pad(std::size_t at) const {
            for (std::size_t l = 0; l < skip_block; ++l)
                to[at + l] = padding;
        }
    };
    // 3D: the runs of the cell at (x, y, z) of the tile's neighbourhood
    // (1 .. 4 each) into b.runs: the walls of the 27 cells around it (nine
    // rows of three), then, with reactions, the fluid of the cell after the
    // particle's own entry (each pair in the cell once too) and of the 13
    // cells after it in (z, y, x) order: the next along x (which follows the
    // cell in its row), the row of three above it along y, the three rows
    // above along z.
    [[gnu::noinline]] static void cell_runs(Buffers& b, int x, int y, int z) {
        const auto index = [](int x, int y, int z) {
            return x + halo_width * (y + halo_width * z);
        };
        int count = 0;
        const auto add = [&](std::uint32_t begin, std::uint32_t end, bool after_own,
                             bool reaction) {
            if (end > begin)
                b.runs[count++] = {begin, end, after_own, reaction};
        };
        const auto fluid_row = [&](int from, int to, int y, int z) {
            const HaloCell& last = b.halo[index(to, y, z)];
            add(b.fluid_at[index(from, y, z)],
                b.fluid_at[index(to, y, z)] + (last.fluid_end - last.begin), false, true);
        };
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy) {
                const HaloCell& last = b.halo[index(x + 1, y + dy, z + dz)];
                add(b.wall_at[index(x - 1, y + dy, z + dz)],
                    b.wall_at[index(x + 1, y + dy, z + dz)] + (last.end - last.fluid_end), false,
                    false);
            }
        const HaloCell& own = b.halo[index(x, y, z)];
        b.own_at = b.fluid_at[index(x, y, z)];
        b.own_begin = own.begin;
        const HaloCell& next = b.halo[index(x + 1, y, z)];
        add(b.own_at, b.fluid_at[index(x + 1, y, z)] + (next.fluid_end - next.begin), true, true);
        fluid_row(x - 1, x + 1, y + 1, z);
        for (int dy = -1; dy <= 1; ++dy)
            fluid_row(x - 1, x + 1, y + dy, z + 1);
        b.run_count = count;
    }

    // Copies the cell's candidates' positions into b, as offsets from its
    // first particle (returned), the runs in order; the padding lanes lie
    // far outside the support.
    Vec<D> gather_positions(const Cell& cell, Buffers& b) const {
        const Vec<D> reference = offset_reference(cell.begin);
        for (int a = 0; a < D; ++a) {
            // Whole vectors at a time, past each run's end (sorted_tail,
            // and the next run or the padding overwrites what lies there):
            // a run is about 8 particles, and a loop of that length costs
            // more in its prologue and remainder than in its body.
            // Indexed from a pointer to the run, in size_t: with the
            // 32-bit index run.begin + c + l, which may wrap, GCC could not
            // tell the loads were contiguous and made them one by one.
            const PositionCopy copy{cells_.sorted_positions(a).data(), b.x[a].data(), reference[a]};
            std::size_t m = 0;
            for (const auto& run : cell.runs) {
                copy(run.begin, run.end, m);
                m += run.end - run.begin;
            }
            fill_lanes(b.x[a].data() + m, 1e18f);
            b.padded = (m + float_lanes - 1) / float_lanes * float_lanes;
        }
        return reference;
    }
    // The position of sorted entry k, from which the buffers' offsets are.
    Vec<D> offset_reference(std::uint32_t k) const {
        Vec<D> reference;
        for (int a = 0; a < D; ++a)
            reference[a] = cells_.sorted_positions(a)[k];
        return reference;
    }
    // Copies one field of the cell's candidates into `out` as
    // gather_positions does, then `padding` up to the padded end.
    void gather(const Cell& cell, const std::vector<float>& field, std::vector<float>& out,
                float padding) const {
        const FieldCopy copy{field.data(), out.data(), padding};
        std::size_t m = 0;
        for (const auto& run : cell.runs) {
            copy(run.begin, run.end, m);
            m += run.end - run.begin;
        }
        fill_lanes(out.data() + m, padding);
    }
    // Writes one vector of `value` from `at`: the padding, which that
    // reaches (the buffers have room past it).
    static void fill_lanes(float* at, float value) {
        for (std::uint32_t l = 0; l < float_lanes; ++l)
            at[l] = value;
    }
    FVec offset(std::uint32_t k, const Vec<D>& reference) const {
        FVec x;
        for (int a = 0; a < D; ++a)
            x[a] = float(cells_.sorted_positions(a)[k] - reference[a]);
        return x;
    }
    // 3D: a particle's blocks within reach, as the density pass found them,
    // for the pressure pass of the same step to read instead of testing the
    // blocks again: the tiles' layouts and the positions are the same in
    // both (the tests were a fifth of the pressure pass). A slot a particle:
    // a header (the count, those before the reactions' runs, whether its
    // own term is added; `unsaved` when they did not fit) and the blocks'
    // first entries.
    // Slots of 16 short integers, twice as many when too small (density),
    // up to 64.
    struct NearBlocks {
        static constexpr std::size_t largest_slot = 64;
        static constexpr std::uint16_t unsaved = 0xffff;
        std::uint16_t* slot = nullptr;
        std::size_t slot_size = 16;
        bool save = false, load = false;
    };
    // The 3D passes' sum for a particle at x_i and a kernel of support
    // `support`, over the runs of candidates in `lanes`; each term of a run
    // with reaction, times `reaction` (+1 or -1), is also added to that
    // candidate's entry of `reaction_sums` (the term the pair gives it).
    // The blocks of skip_block candidates with none within the support are
    // skipped: a sixth of 3D's candidates are within it (its ball in 27
    // cells) and about half of the blocks of 8 have none (on
    // dam_break_water_3d the pressure pass 203-214 -> 138-140 ns a
    // particle-step, the density pass 79-81 -> 68). In 2D a third are
    // within and a quarter of the blocks have none: both passes measured
    // no faster or slower there (docs/benchmarks.md).
    // Exact: a skipped term is 0 (the kernels are 0 from q = 1), and the
    // test keeps a margin so that round-off cannot skip a block with a term
    // in it. The sum runs a lane at a time in candidate order, then over the
    // lanes by halves: it does not depend on the thread count.
    template <class T, int reaction, class Term>
    static T sum_pairs_once(const Lanes& lanes, std::uint32_t k_i, const FVec& x_i, float support,
                            const Term& term_argument, const std::array<float*, D>& reaction_sums,
                            NearBlocks near = {}) {
        static_assert(D == 3);
        const Term term = term_argument;
        const Lanes l = lanes; // local copies, as in sum_candidates
        const float reach2 = support * support * 1.0001f;
        const float xi = x_i.x, yi = x_i.y, zi = x_i.z;
        constexpr int parts = std::is_same_v<T, float> ? 1 : D;
        alignas(64) float sums[parts][skip_block] = {};
        // First the blocks with a candidate within reach, listed without
        // a branch: a branch a block, taken about half the time at
        // random, cost more in mispredictions than the skipped terms.
        // Or the list the density pass saved (NearBlocks).
        std::uint32_t* const near_blocks = l.near_blocks;
        std::size_t near_count = 0, before_forward = 0;
        const std::uint32_t own = l.own_at + (k_i - l.own_begin);
        bool self = false;
        if (near.load && near.slot[0] != NearBlocks::unsaved) {
            const std::uint16_t header = near.slot[0];
            near_count = header & 63;
            before_forward = header >> 6 & 63;
            self = (header >> 12 & 1) != 0;
            for (std::size_t k = 0; k < near_count; ++k)
                near_blocks[k] = near.slot[1 + k];
        } else {
            for (int r = 0; r < l.run_count; ++r) {
                const Run run = l.runs[r];
                self = self || run.after_own;
                for (std::uint32_t block = run.after_own ? own + 1 : run.begin; block < run.end;
                     block += skip_block) {
                    near_blocks[near_count] = block;
                    near_count += any_within(l, block, xi, yi, zi, reach2) ? 1 : 0;
                }
                if (!run.reaction)
                    before_forward = near_count;
            }
            if (near.save) {
                const bool fits = near_count < near.slot_size && l.padded <= 0xffff;
                near.slot[0] =
                    fits ? std::uint16_t(near_count | before_forward << 6 | (self ? 1 : 0) << 12)
                         : NearBlocks::unsaved;
                for (std::size_t k = 0; fits && k < near_count; ++k)
                    near.slot[1 + k] = static_cast<std::uint16_t>(near_blocks[k]);
            }
        }
        for (std::size_t k = 0; k < before_forward; ++k) {
            const std::size_t block = near_blocks[k];
#pragma omp simd
            for (std::size_t c = 0; c < skip_block; ++c) {
                const T t = term(block + c);
                if constexpr (parts == 1)
                    sums[0][c] += t;
                else {
                    sums[0][c] += t.x;
                    sums[1][c] += t.y;
                    sums[2][c] += t.z;
                }
            }
        }
        if constexpr (reaction != 0) {
            float* const r0 = reaction_sums[0];
            float* const r1 = reaction_sums[parts == 1 ? 0 : 1];
            float* const r2 = reaction_sums[parts == 1 ? 0 : 2];
            for (std::size_t k = before_forward; k < near_count; ++k) {
                const std::size_t block = near_blocks[k];
#pragma omp simd
                for (std::size_t c = 0; c < skip_block; ++c) {
                    const T t = term(block + c);
                    if constexpr (parts == 1) {
                        sums[0][c] += t;
                        r0[block + c] += reaction * t;
                    } else {
                        sums[0][c] += t.x;
                        sums[1][c] += t.y;
                        sums[2][c] += t.z;
                        r0[block + c] += reaction * t.x;
                        r1[block + c] += reaction * t.y;
                        r2[block + c] += reaction * t.z;
                    }
                }
            }
        }
        T total{};
        for (int a = 0; a < parts; ++a) {
            for (std::size_t half = skip_block / 2; half > 0; half /= 2)
                for (std::size_t c = 0; c < half; ++c)
                    sums[a][c] += sums[a][c + half];
            if constexpr (parts == 1)
                total = sums[0][0];
            else
                total[a] = sums[a][0];
        }
        // The particle's own term (the runs after it leave it out): m W(0)
        // in the density, 0 in the pressure's.
        if (self)
            total += term(own);
        return total;
    }
    // Whether a candidate of the block from `block` lies nearer than
    // sqrt(reach2) to (xi, yi, zi) (3D).
    static bool any_within(const Lanes& l, std::size_t block, float xi, float yi, float zi,
                           float reach2) {
#if SPHCLIP_SIMD_BITS >= 256
        // The lanes' signs in one move: the vectorised loop's sum over the
        // lanes took 7 instructions more a block.
        static_assert(skip_block == 8);
        const __m256 dx = _mm256_sub_ps(_mm256_set1_ps(xi), _mm256_loadu_ps(l.x + block));
        const __m256 dy = _mm256_sub_ps(_mm256_set1_ps(yi), _mm256_loadu_ps(l.y + block));
        const __m256 dz = _mm256_sub_ps(_mm256_set1_ps(zi), _mm256_loadu_ps(l.z + block));
        const __m256 r2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                        _mm256_mul_ps(dz, dz));
        return _mm256_movemask_ps(_mm256_cmp_ps(r2, _mm256_set1_ps(reach2), _CMP_LT_OQ)) != 0;
#else
        // On plain floats: through glm's vectors GCC left this loop scalar.
        const float *x = l.x + block, *y = l.y + block, *z = l.z + block;
        int near = 0;
#pragma omp simd reduction(+ : near)
        for (std::size_t c = 0; c < skip_block; ++c) {
            const float dx = xi - x[c], dy = yi - y[c], dz = zi - z[c];
            near += dx * dx + dy * dy + dz * dz < reach2 ? 1 : 0;
        }
        return near > 0;
#endif
    }
    // sum over m < padded of term(m), a float or an array of D; an OpenMP
    // simd reduction, so the compiler vectorises it.
    template <class T, class Term>
    static T sum_candidates(std::size_t padded, const Term& term_argument) {
        const Term term = term_argument; // a local copy, as in neighbour_sum.hpp
        if constexpr (std::is_same_v<T, float>) {
            float s = 0;
#pragma omp simd reduction(+ : s)
            for (std::size_t m = 0; m < padded; ++m)
                s += term(m);
            return s;
        } else if constexpr (D == 2) {
            float x = 0, y = 0;
#pragma omp simd reduction(+ : x, y)
            for (std::size_t m = 0; m < padded; ++m) {
                const T t = term(m);
                x += t.x;
                y += t.y;
            }
            return {x, y};
        } else {
            float x = 0, y = 0, z = 0;
#pragma omp simd reduction(+ : x, y, z)
            for (std::size_t m = 0; m < padded; ++m) {
                const T t = term(m);
                x += t.x;
                y += t.y;
                z += t.z;
            }
            return {x, y, z};
        }
    }

    CellNeighbourhoods<D> cells_;
    SortedFields sorted_;
    // 3D: each fluid particle's sums by sorted entry (for_each_cell).
    std::array<std::vector<float>, D> sums_;
    // 3D, pairs once: the density pass's blocks within reach by sorted
    // entry (NearBlocks), for the pressure pass when near_saved_ (the same
    // cells and support).
    std::vector<std::uint16_t> near_blocks_;
    bool near_saved_ = false;
    float near_support_ = 0;
    std::size_t near_slot_size_ = 16, next_near_slot_size_ = 16;
    std::uint16_t* near_slot(std::size_t k) {
        return near_blocks_.data() + k * near_slot_size_;
    }
    std::vector<Buffers> buffers_;
    // 3D: each tile's neighbourhood, by CellNeighbourhoods::tile_index, as
    // the first pass over the cells found it (tile_halo's 216 look-ups a
    // tile were 2% of the step), for the next pass when halos_saved_.
    struct TileHalo {
        std::array<HaloCell, halo_cells> halo;
        typename CellNeighbourhoods<D>::Coordinates corner;
    };
    std::vector<TileHalo> halos_;
    bool halos_saved_ = false;
};

// The variant behind the interface: the kernel chosen by name here, so that
// each kernel's loops are this variant's.
template <int D>
class Passes final : public SinglePasses<D> {
  public:
    void find_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                    Real radius, PairTerms pair_terms, const CellSkin<D>& skin) override {
        cells_.find_cells(fluid, boundary, radius, pair_terms, skin);
    }
    Real refresh_cells(std::span<const Vec<D>> fluid) override {
        return cells_.refresh_cells(fluid);
    }
    void density(const Params<D>& params, KernelKind kind, const BoundaryParticles<D>* boundary,
                 State<D>& state) override {
        with_smooth_kernel(kind, params.h, [&](const auto& kernel) {
            cells_.density(params, kernel, boundary, state);
        });
    }
    void pressure_acceleration(const Params<D>& params, KernelKind kind,
                               const BoundaryParticles<D>* boundary,
                               const PairViscosities& viscosities, State<D>& state) override {
        with_smooth_kernel(kind, params.h, [&](const auto& kernel) {
            cells_.pressure_acceleration(params, kernel, boundary, viscosities, state);
        });
    }

    std::size_t float_lanes() const override { return SPHCLIP_SIMD_VARIANT::float_lanes; }

  private:
    // The scene refuses single precision with the seed's spiky kernel.
    template <class F>
    static void with_smooth_kernel(KernelKind kind, Real support, const F& f) {
        if (kind == KernelKind::cubic_spline)
            f(CubicSpline<D>(support));
        else if (kind == KernelKind::wendland_c2)
            f(WendlandC2<D>(support));
        else
            throw std::logic_error("single precision needs a kernel smooth at the origin");
    }

    CellPasses<D> cells_;
};

template <int D>
std::unique_ptr<SinglePasses<D>> make_passes() {
    return std::make_unique<Passes<D>>();
}
template std::unique_ptr<SinglePasses<2>> make_passes<2>();
template std::unique_ptr<SinglePasses<3>> make_passes<3>();

} // namespace sph::SPHCLIP_SIMD_VARIANT
