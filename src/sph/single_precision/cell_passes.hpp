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
// In 3D each pair of fluid particles in two different cells is computed
// once, by the cell that comes first along the Morton curve, which adds the
// pair's term to its particle and the term's reaction to the other's
// (Newton's third law; for_each_cell): half the pair terms, with the cells
// taken a tile of 4^3 at a time so that their neighbourhoods stay cached.
// Taking each pair from both sides, as 2D does, measured at par there
// (docs/benchmarks.md).
//
// Accuracy: positions are copied as offsets from the cell's first particle,
// computed in double, so a domain far from the origin loses nothing; an
// offset is at most two cells long and keeps 24 bits. The per-particle sums
// are taken in float and stored in double. Each particle's sum runs over the
// candidates in the cells' sorted order (in 3D: its own terms so, then the
// reactions in the tiles' fixed order), so the result is the same with any
// thread count. The float form of each formula is the double one's
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
    // search. `boundary` may be null.
    void find_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                    Real radius) {
        if (boundary)
            cells_.build(fluid, boundary->positions(), radius, &boundary->static_bounds(),
                         [boundary](const Box<D>& box, std::vector<std::uint32_t>& out) {
                             boundary->within(box, out);
                         });
        else
            cells_.build(fluid, {}, radius);
    }

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
        for_each_cell(once ? 1 : 0, [&](const Cell& cell, Buffers& b, const Vec<D>& reference) {
            gather(cell, b, sorted_.mass, b.mass, 0.f);
            const Lanes l = b.lanes();
            for (std::uint32_t k = cell.begin; k < cell.fluid_end; ++k) {
                const FVec x_i = offset(k, reference);
                const auto term = [=](std::size_t m) {
                    const FVec x_ij = x_i - l.position(m);
                    const float r2 = glm::dot(x_ij, x_ij);
                    return l.mass[m] * kernel.W(std::sqrt(r2));
                };
                if constexpr (D == 2)
                    state.density[order[k]] = sum_candidates<float>(l.padded, term);
                else if (!once)
                    state.density[order[k]] =
                        sum_pairs_once<float, 0>(l, x_i, kernel.h, term, {}, l.padded);
                else
                    sums_[0][k] +=
                        sum_pairs_once<float, 1>(l, x_i, kernel.h, term, b.reactions(), b.forward);
            }
        });
        if (once)
            finish([&](std::uint32_t k, const FVec& sum) { state.density[order[k]] = sum[0]; });
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
                            &sorted_.volume, &sorted_.wall})
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
                sorted_.wall[k] = 0;
            } else {
                const Real volume = boundary->volumes()[cells_.wall(j - n)];
                sorted_.mass[k] = float(params.rest_density * volume);
                sorted_.density[k] = 0; // the fluid particle's, in the loop
                sorted_.pressure_term[k] = 0;
                sorted_.volume[k] = float(volume);
                sorted_.wall[k] = 1;
            }
        }
        const bool once = D == 3 && params.pair_terms == PairTerms::once;
        const bool hydrostatic_walls = params.wall_gravity != Vec<D>(0);
        const FVec wall_gravity(params.wall_gravity);
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
            for_each_cell(once ? D : 0, [&](const Cell& cell, Buffers& b, const Vec<D>& reference) {
                for (int a = 0; a < D; ++a)
                    gather(cell, b, sorted_.velocity[a], b.velocity[a], 0.f);
                gather(cell, b, sorted_.mass, b.mass, 0.f);
                gather(cell, b, sorted_.pressure_term, b.pressure_term, 0.f);
                gather(cell, b, sorted_.wall, b.wall, 0.f);
                if constexpr (artificial)
                    gather(cell, b, sorted_.density, b.density, 1.f);
                if constexpr (laminar)
                    gather(cell, b, sorted_.volume, b.volume, 0.f);
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
                        const float g = kernel.dW_over_r(r);
                        // A wall's pressure term and density are stored as 0
                        // and its `wall` as 1, so these sums pick exactly the
                        // fluid's or the wall's value. Not a select: GCC made
                        // the load under one a masked load, and then kept the
                        // loop's two sums in memory, a store and a load in the
                        // critical path of every vector of candidates.
                        const float wall = l.wall[m];
                        float p_b = pt_i;
                        // (p_i + p_b) / rho_i^2 with the wall's hydrostatic rise,
                        // p_b = max(p_i + rho_i g . (x_b - x_i), 0).
                        if constexpr (hydrostatic)
                            p_b =
                                std::max(pt_i - glm::dot(wall_gravity, x_ij) * inverse_rho_i, 0.f);
                        float factor = pt_i + (l.pressure_term[m] + wall * p_b);
                        if constexpr (artificial)
                            factor += Pi(v_dot_x, rho_i + (l.density[m] + wall * rho_i), r2);
                        const float pressure = -l.mass[m] * factor * g;
                        float viscous = 0;
                        if constexpr (laminar)
                            viscous = viscous_scale * morris(l.volume[m], r2 * g, r2);
                        return pressure * x_ij + viscous * v_ij;
                    };
                    // Between fluid particles the term is antisymmetric (the
                    // same mass; p_i/rho_i^2 + p_j/rho_j^2, Pi_ij and the
                    // laminar 2 mu m / (rho_i rho_j) symmetric in i and j), so
                    // the candidate's reaction is -1 times it.
                    if constexpr (D == 2)
                        state.acceleration[order[k]] = Vec<D>(sum_candidates<FVec>(l.padded, term));
                    else if (!once)
                        state.acceleration[order[k]] =
                            Vec<D>(sum_pairs_once<FVec, 0>(l, x_i, kernel.h, term, {}, l.padded));
                    else {
                        const FVec a_i = sum_pairs_once<FVec, -1>(l, x_i, kernel.h, term,
                                                                  b.reactions(), b.forward);
                        for (int a = 0; a < D; ++a)
                            sums_[a][k] += a_i[a];
                    }
                }
            });
            if (once)
                finish([&](std::uint32_t k, const FVec& sum) {
                    state.acceleration[order[k]] = Vec<D>(sum);
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
        std::vector<float> mass, density, pressure_term, volume, wall;
    };
    // A cell's neighbourhood as the loops read it: plain pointers, copied
    // into each loop's closure, so GCC sees that no load changes in the loop
    // (through a reference to the vectors it keeps the loop scalar).
    struct Lanes {
        const float *x, *y, *z, *vx, *vy, *vz; // z, vz: 3D only
        const float *mass, *density, *pressure_term, *volume, *wall;
        std::size_t padded;
        std::uint32_t* near_blocks; // scratch: padded / skip_block entries

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
    // 3D: where a cell's neighbourhood lies in a thread's buffers (lay_out):
    // pieces of the sorted arrays, each copied to `at`, one a run at most.
    struct Piece {
        std::uint32_t begin, end, at;
        bool padded; // the last of its segment: padding follows it
    };
    static constexpr int max_pieces = D == 2 ? 9 : 27;
    // One thread's copy of a cell's neighbourhood, padded to whole vectors.
    // A cache line of its own: a thread writes `padded` for every cell, and
    // sharing its line with the next thread's vectors cost 2D a third of
    // the second thread's gain.
    struct alignas(64) Buffers {
        std::array<std::vector<float>, D> x, velocity;
        std::vector<float> mass, density, pressure_term, volume, wall;
        std::vector<std::uint32_t> near_blocks;
        // 3D: the terms this cell's particles gave the candidates from
        // `forward` on, by candidate (reaction[0] alone for the density).
        std::array<std::vector<float>, D> reaction;
        std::array<Piece, max_pieces> pieces;
        int piece_count = 0;
        std::uint32_t forward = 0; // where the candidates with a reaction start
        std::size_t padded = 0;

        Lanes lanes() {
            return {
                x[0].data(),        x[1].data(),        D == 3 ? x[D - 1].data() : nullptr,
                velocity[0].data(), velocity[1].data(), D == 3 ? velocity[D - 1].data() : nullptr,
                mass.data(),        density.data(),     pressure_term.data(),
                volume.data(),      wall.data(),        padded,
                near_blocks.data()};
        }
        std::array<float*, D> reactions() {
            std::array<float*, D> r;
            for (int a = 0; a < D; ++a)
                r[a] = reaction[a].data();
            return r;
        }
    };

    using Cell = typename CellNeighbourhoods<D>::Cell;
    using Range = typename CellNeighbourhoods<D>::Range;

    // Calls work(cell, buffers, reference) for every cell holding fluid, in
    // parallel, with this thread's buffers holding the cell's candidates'
    // positions as offsets from `reference` (gather_positions).
    // 3D: each fluid pair in two different cells is taken once (Newton's
    // third law), by the cell first along the Morton curve: its particles
    // run over the walls of the cells before it, its own particles and all
    // of the cells after it, and write the terms they give those cells'
    // particles to b.reaction (`parts` floats a candidate), which are added
    // into sums_ when the cell is done. The cells go colour by colour, so no
    // two threads add into one particle's sums at once, and each sum's
    // order of additions is the same with any thread count. work adds each
    // particle's own sum into sums_; finish then hands the sums over.
    template <class Work>
    void for_each_cell(int parts, const Work& work) {
        prepare_buffers();
        if (D == 2 || parts == 0) {
            const std::size_t count = cells_.cell_count();
#pragma omp parallel for schedule(dynamic, 16)
            for (std::size_t c = 0; c < count; ++c) {
                const Cell cell = cells_.cell(c);
                if (!cell.has_fluid())
                    continue;
                Buffers& b = buffers_[omp_get_thread_num()];
                b.piece_count = 0; // the runs in order (gather_positions)
                work(cell, b, gather_positions(cell, b));
            }
        } else if constexpr (D == 3) {
            cells_.tile_cells();
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
                    for (std::size_t t = 0; t < cells_.tile_count(q); ++t)
                        for (std::uint32_t i = cells_.tile_start(q, t);
                             i < cells_.tile_start(q, t + 1); ++i) {
                            const Cell cell = cells_.cell(cells[i]);
                            lay_out(cell, b);
                            for (int a = 0; a < parts; ++a)
                                std::fill(b.reaction[a].data() + b.forward,
                                          b.reaction[a].data() + b.padded, 0.f);
                            work(cell, b, gather_positions(cell, b));
                            for (int p = 0; p < b.piece_count; ++p) {
                                const Piece piece = b.pieces[p];
                                if (piece.at < b.forward)
                                    continue;
                                // Walls' entries too: their sums are never read.
                                for (int a = 0; a < parts; ++a) {
                                    float* const to = sums_[a].data() + piece.begin;
                                    const float* const from = b.reaction[a].data() + piece.at;
#pragma omp simd
                                    for (std::uint32_t t = 0; t < piece.end - piece.begin; ++t)
                                        to[t] += from[t];
                                }
                            }
                        }
                }
            }
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
        for (Buffers& b : buffers_) {
            for (int a = 0; a < D; ++a) {
                resize_with_headroom(b.x[a], size);
                resize_with_headroom(b.velocity[a], size);
                if constexpr (D == 3)
                    resize_with_headroom(b.reaction[a], size);
            }
            for (auto* field : {&b.mass, &b.density, &b.pressure_term, &b.volume, &b.wall})
                resize_with_headroom(*field, size);
            resize_with_headroom(b.near_blocks, size / skip_block + 1);
        }
    }

    // 3D: where each of the cell's candidates goes in b: the walls of the
    // runs before the cell's own, the cell itself, the runs after it
    // (b.forward on), each segment starting on a whole block, the last
    // piece of each followed by padding.
    void lay_out(const Cell& cell, Buffers& b) const {
        int p = 0;
        std::uint32_t m = 0;
        const auto add = [&](std::uint32_t begin, std::uint32_t end) {
            if (end > begin) {
                b.pieces[p++] = {begin, end, m, false};
                m += end - begin;
            }
        };
        const auto close_segment = [&](int first) {
            if (p > first)
                b.pieces[p - 1].padded = true;
            m = (m + skip_block - 1) / skip_block * skip_block;
        };
        const int runs = static_cast<int>(cell.runs.size());
        int own = 0;
        while (cell.runs[own].begin != cell.begin)
            ++own;
        for (int r = 0; r < own; ++r)
            add(cells_.fluid_end(cell.runs[r]), cell.runs[r].end);
        close_segment(0);
        int first = p;
        add(cell.runs[own].begin, cell.runs[own].end);
        close_segment(first);
        b.forward = m;
        first = p;
        for (int r = own + 1; r < runs; ++r)
            add(cell.runs[r].begin, cell.runs[r].end);
        close_segment(first);
        b.padded = m;
        b.piece_count = p;
    }

    // Copies the cell's candidates' positions into b, as offsets from its
    // first particle (returned); the padding lanes lie far outside the
    // support: the runs in order, or, with pieces, as lay_out put them.
    Vec<D> gather_positions(const Cell& cell, Buffers& b) const {
        Vec<D> reference;
        for (int a = 0; a < D; ++a)
            reference[a] = cells_.sorted_positions(a)[cell.begin];
        for (int a = 0; a < D; ++a) {
            const Real* x = cells_.sorted_positions(a).data();
            float* out = b.x[a].data();
            const Real r = reference[a];
            // Whole vectors at a time, past each run's end (sorted_tail,
            // and the next run or the padding overwrites what lies there):
            // a run is about 8 particles, and a loop of that length costs
            // more in its prologue and remainder than in its body.
            // Indexed from a pointer to the run, in size_t: with the
            // 32-bit index run.begin + c + l, which may wrap, GCC could not
            // tell the loads were contiguous and made them one by one.
            const auto copy = [&](std::uint32_t begin, std::uint32_t end, std::size_t at) {
                const Real* from = x + begin;
                float* to = out + at;
                const std::size_t length = end - begin;
                for (std::size_t c = 0; c < length; c += float_lanes)
                    for (std::size_t l = 0; l < float_lanes; ++l)
                        to[c + l] = float(from[c + l] - r);
            };
            if (b.piece_count == 0) {
                std::size_t m = 0;
                for (const auto& run : cell.runs) {
                    copy(run.begin, run.end, m);
                    m += run.end - run.begin;
                }
                fill_lanes(out + m, 1e18f);
                b.padded = (m + float_lanes - 1) / float_lanes * float_lanes;
            } else {
                for (int p = 0; p < b.piece_count; ++p) {
                    const Piece piece = b.pieces[p];
                    copy(piece.begin, piece.end, piece.at);
                    if (piece.padded)
                        fill_lanes(out + piece.at + (piece.end - piece.begin), 1e18f);
                }
            }
        }
        return reference;
    }
    // Copies one field of the cell's candidates into `out` as
    // gather_positions does, then `padding` up to the padded ends.
    void gather(const Cell& cell, const Buffers& b, const std::vector<float>& field,
                std::vector<float>& out, float padding) const {
        // As in gather_positions: whole vectors, past each run's end.
        const auto copy = [&](std::uint32_t begin, std::uint32_t end, std::size_t at) {
            for (std::uint32_t c = 0; c < end - begin; c += float_lanes)
                std::memcpy(out.data() + at + c, field.data() + begin + c,
                            float_lanes * sizeof(float));
        };
        if (b.piece_count == 0) {
            std::size_t m = 0;
            for (const auto& run : cell.runs) {
                copy(run.begin, run.end, m);
                m += run.end - run.begin;
            }
            fill_lanes(out.data() + m, padding);
        } else {
            for (int p = 0; p < b.piece_count; ++p) {
                const Piece piece = b.pieces[p];
                copy(piece.begin, piece.end, piece.at);
                if (piece.padded)
                    fill_lanes(out.data() + piece.at + (piece.end - piece.begin), padding);
            }
        }
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
    // The 3D passes' sum for a particle at x_i and a kernel of support
    // `support`, over the candidates lay_out put in `lanes`; each term from
    // l.forward on, times `reaction` (+1 or -1), is also added to that
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
    static T sum_pairs_once(const Lanes& lanes, const FVec& x_i, float support,
                            const Term& term_argument, const std::array<float*, D>& reaction_sums,
                            std::size_t forward) {
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
        std::uint32_t* const near_blocks = l.near_blocks;
        std::size_t near_count = 0;
        for (std::size_t block = 0; block < forward; block += skip_block) {
            near_blocks[near_count] = static_cast<std::uint32_t>(block);
            near_count += any_within(l, block, xi, yi, zi, reach2) ? 1 : 0;
        }
        const std::size_t before_forward = near_count;
        for (std::size_t block = forward; block < l.padded; block += skip_block) {
            near_blocks[near_count] = static_cast<std::uint32_t>(block);
            near_count += any_within(l, block, xi, yi, zi, reach2) ? 1 : 0;
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
        // Reaction 0 (both sides) passes the padded end as `forward`: no
        // block lies after it, and it has no reaction sums.
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
    std::vector<Buffers> buffers_;
};

// The variant behind the interface: the kernel chosen by name here, so that
// each kernel's loops are this variant's.
template <int D>
class Passes final : public SinglePasses<D> {
  public:
    void find_cells(std::span<const Vec<D>> fluid, const BoundaryParticles<D>* boundary,
                    Real radius) override {
        cells_.find_cells(fluid, boundary, radius);
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
