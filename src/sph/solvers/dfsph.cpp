#include "sph/solvers/dfsph.hpp"

#include "sph/headroom.hpp"
#include "sph/integrate.hpp"
#include "sph/neighbours/neighbour_sum.hpp"
#include "sph/pair_direction.hpp"
#include "sph/pressure_acceleration.hpp"
#include "sph/solvers/density_with_walls.hpp"
#include "sph/thread_runs.hpp"
#include "sph/vector_clones.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>
#include <span>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

// Notation. With g_ij = m grad W_ij (fluid pairs), w_ib = rho0 V_b grad W_ib
// (wall pairs) and W_i = sum_b w_ib, a wall particle is the mirror image
// of the fluid particle beside it (a ghost): it has the particle's pressure,
// p_b = p_i, and the mirror image of its velocity about the wall's,
// 2 v_b - v_i. So the rate of compression is
//   D rho_i / Dt = sum_j g_ij . (v_i - v_j) + 2 sum_b w_ib . (v_i - v_b)
// (v_b = 0 but on a paddle, sph/boundaries/paddles.hpp; Bender & Koschier
// 2017, eq. 9's source with the walls' term) and a velocity correction with
// per-particle stiffness s
//   dv_i = - sum_j (s_i + s_j) g_ij - 2 s_i W_i
// is the symmetric pressure force with p_i / rho_i^2 = s_i / dt. Written
// D rho / Dt = J v, the correction is dv = -J^T s: the solves are
// orthogonal projections, which take compression out of the velocities
// and never add kinetic energy. With the walls mirrored in the force but
// counted once in the rate (Akinci's term; SPlisHSPlasH counts them once in
// both) until 2026-12-05, the correction was not J's transpose, and a deep
// 3D tank at rest blew up within 0.02 s at any step size or tolerance
// (docs/validation.md, "The deep tank's blow-up"; tests/stability/
// deep_tank_3d.json). Counted once in both, the walls would hold the fluid
// with twice its pressure in the layers beside them. Taking every s_j but s_i as
// zero, the correction changes D rho_i / Dt by -s_i S_i with
//   S_i = |sum_j g_ij + 2 W_i|^2 + sum_j |g_ij|^2,
// so s_i = (D rho_i / Dt) / S_i removes the divergence, and
// s_i = (rho*_i - rho0) / (dt S_i) the predicted compression
// (Bender & Koschier 2017, sec. 3-4, with the density folded into s).
// Units: g in kg m^-(D+1), S in its square, s in m^(D+2) / (kg s).

namespace sph {

namespace {
constexpr Real jacobi_relaxation = 0.5;
// A wall particle counts twice beside a fluid particle, in the force and in
// the rate alike: it mirrors the particle's pressure and velocity (above).
constexpr Real wall_mirror = 2;

// A register's lanes from memory (slice_lanes floats at `at`), and back.
// Through references, not values: a 32-byte vector passed by value changes
// the ABI in a build without AVX (GCC's -Wpsabi).
SPHCLIP_INLINE_IN_CLONES void load_lanes(Lanes& lanes, const float* at) {
    std::memcpy(&lanes, at, sizeof lanes);
}

// lanes[l] = values[index[l]]: AVX2's gather in a build for a processor
// that has it (measured: the solves' iterations 7% faster than the lanes
// loaded one at a time, Intel Xeon); a clone (sph/vector_clones.hpp)
// loads them one at a time, since its source is the baseline's too.
SPHCLIP_INLINE_IN_CLONES void gather_lanes(Lanes& lanes, const float* values,
                                           const std::uint32_t* index) {
#if defined(__AVX2__)
    __m256i j;
    std::memcpy(&j, index, sizeof j);
    lanes = Lanes(_mm256_i32gather_ps(values, j, 4));
#else
    for (std::size_t l = 0; l < slice_lanes; ++l)
        lanes[l] = values[index[l]];
#endif
}

// A particle's floats as the pair loops gather them: four to a particle
// (a 16-byte load), its D components then one more (the padding, or the
// density beside a position).
using Quad = float __attribute__((vector_size(16)));

// out[c][l] = quads[4 index[l] + c] for the 4 components c: the lanes'
// quads loaded whole and transposed in registers, 8 loads and 11 shuffles
// where gathering by component takes 4 gathers of 8 (the rate and the
// viscosities' passes, measured: docs/benchmarks.md, "The solves' loads").
SPHCLIP_INLINE_IN_CLONES void gather_quads(std::array<Lanes, 4>& out, const float* quads,
                                           const std::uint32_t* index) {
    static_assert(slice_lanes == 8);
    std::array<Quad, 8> q;
    for (std::size_t l = 0; l < 8; ++l)
        std::memcpy(&q[l], quads + 4 * std::size_t(index[l]), sizeof(Quad));
    // [q0 | q4], [q1 | q5], ...: each 128-bit half then transposes as 4 x 4.
    const Lanes a0 = __builtin_shufflevector(q[0], q[4], 0, 1, 2, 3, 4, 5, 6, 7);
    const Lanes a1 = __builtin_shufflevector(q[1], q[5], 0, 1, 2, 3, 4, 5, 6, 7);
    const Lanes a2 = __builtin_shufflevector(q[2], q[6], 0, 1, 2, 3, 4, 5, 6, 7);
    const Lanes a3 = __builtin_shufflevector(q[3], q[7], 0, 1, 2, 3, 4, 5, 6, 7);
    const Lanes t0 = __builtin_shufflevector(a0, a1, 0, 8, 1, 9, 4, 12, 5, 13);
    const Lanes t1 = __builtin_shufflevector(a0, a1, 2, 10, 3, 11, 6, 14, 7, 15);
    const Lanes t2 = __builtin_shufflevector(a2, a3, 0, 8, 1, 9, 4, 12, 5, 13);
    const Lanes t3 = __builtin_shufflevector(a2, a3, 2, 10, 3, 11, 6, 14, 7, 15);
    out[0] = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
    out[1] = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
    out[2] = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
    out[3] = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
}

// The same for a slice's own particles, first .. first + 7, whose quads
// are consecutive.
SPHCLIP_INLINE_IN_CLONES void load_quads(std::array<Lanes, 4>& out, const float* quads,
                                         std::size_t first) {
    std::array<std::uint32_t, 8> index;
    for (std::size_t l = 0; l < 8; ++l)
        index[l] = std::uint32_t(first + l);
    gather_quads(out, quads, index.data());
}

// Per lane: doubles, and the counts a slice's lanes compare.
using Doubles = double __attribute__((vector_size(8 * slice_lanes)));
using Counts = std::uint32_t __attribute__((vector_size(4 * slice_lanes)));

// Lanes of 64-bit integers: the masks of Doubles.
using Wide = std::int64_t __attribute__((vector_size(8 * slice_lanes)));

// out = the lanes' square roots (one vector instruction where there is one).
SPHCLIP_INLINE_IN_CLONES void square_roots(Doubles& out, const Doubles& in) {
#if defined(__AVX512F__)
    // Masked, all lanes on: the unmasked intrinsic sets off GCC 12's
    // -Wmaybe-uninitialized.
    out = Doubles(_mm512_mask_sqrt_pd(__m512d(in), 0xff, __m512d(in)));
#elif defined(__AVX__)
    using Half = double __attribute__((vector_size(32)));
    const Half low = _mm256_sqrt_pd(__m256d(__builtin_shufflevector(in, in, 0, 1, 2, 3)));
    const Half high = _mm256_sqrt_pd(__m256d(__builtin_shufflevector(in, in, 4, 5, 6, 7)));
    out = __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
#else
    out = in;
    for (std::size_t l = 0; l < slice_lanes; ++l)
        out[l] = std::sqrt(out[l]);
#endif
}

std::size_t slice_count(std::size_t n) {
    return (n + slice_lanes - 1) / slice_lanes;
}

// The slices this thread of a parallel region takes in a pass over them
// (sph/thread_runs.hpp), the runs of equal entries (columns).
auto thread_slices(const std::uint32_t* columns, std::size_t slices) {
    return this_thread_run(slices, columns[slices], [=](std::size_t k) { return columns[k]; });
}
} // namespace

template <int D>
void DfsphSolver<D>::load_velocities(const State<D>& state) {
    const std::size_t n = state.size();
    // Whole slices: the lanes past the last particle read 0.
    resize_with_headroom(velocity_f_, 4 * slice_count(n) * slice_lanes);
    float* rounded = velocity_f_.data();
    const std::uint32_t* row = slice_row_.data();
    std::array<Real*, D> placed;
    for (int k = 0; k < D; ++k) {
        placed_velocity_[k].resize(n);
        placed[k] = placed_velocity_[k].data();
    }
#pragma omp parallel for schedule(static)
    for (std::size_t place = 0; place < n; ++place)
        for (int k = 0; k < D; ++k) {
            placed[k][place] = state.velocity[row[place]][k];
            rounded[4 * place + k] = float(placed[k][place]);
        }
}

template <int D>
void DfsphSolver<D>::store_velocities(State<D>& state) const {
    const std::size_t n = state.size();
    const std::uint32_t* row = slice_row_.data();
#pragma omp parallel for schedule(static)
    for (std::size_t place = 0; place < n; ++place)
        for (int k = 0; k < D; ++k)
            state.velocity[row[place]][k] = placed_velocity_[k][place];
}

template <int D>
typename DfsphSolver<D>::SliceView DfsphSolver<D>::slice_view() const {
    SliceView view{
        slice_start_.data(), slice_row_.data(), slice_index_.data(), {}, velocity_f_.data()};
    for (int k = 0; k < D; ++k)
        view.gradient[k] = slice_gradient_[k].data();
    return view;
}

template <int D>
template <class Kernel>
SPHCLIP_CLONED void DfsphSolver<D>::prepare(const Params<D>& params, const Kernel& kernel,
                                            StepContext<D>& context, State<D>& state) {
    const std::size_t n = state.size();
    // A summed density is summed below, in the pass that makes the pairs'
    // gradients (its r and the loads of x_j shared), timed as the density.
    const bool summed = params.density_model != DensityModel::carried;
    if (summed)
        context.find_neighbours(state.position, params.h);
    else
        find_neighbours_and_carried_density(params, kernel, context, state);

    std::optional<StageTimes::Scope> timed(std::in_place, context.stages, Stage::density);
    factor_.resize(n);
    stiffness_.resize(n);
    // Whole slices: the lanes past the last particle read 0.
    const std::size_t slices = slice_count(n);
    resize_with_headroom(stiffness_f_, slices * slice_lanes);
    stiffness_sum_.resize(n);
    source_.resize(n);
    next_sum_.resize(n);
    // The slices' rows, longest first within each window of
    // window_slices slices (SELL-C-sigma), and their columns: as many as
    // the slice's longest row.
    {
        const NeighbourList& pairs = context.neighbours;
        slice_start_.resize(slices + 1);
        resize_with_headroom(slice_row_, slices * slice_lanes);
        slice_place_.resize(n);
        std::uint32_t* columns = slice_start_.data();
        std::uint32_t* row = slice_row_.data();
        std::uint32_t* place_of = slice_place_.data();
        const std::uint32_t* start = pairs.start.data();
        const std::size_t window = window_slices * slice_lanes;
#pragma omp parallel for schedule(static)
        for (std::size_t first = 0; first < slices * slice_lanes; first += window) {
            const std::size_t last = std::min(n, first + window);
            const auto length = [&](std::uint32_t i) {
                return start[i + 1] - start[i];
            };
            // Sorted as keys (shortest last, ties in particle order: the
            // same rows for any thread count): the row's length above its
            // place in the window.
            static_assert(window_slices * slice_lanes <= 256);
            if (window_slices > 1) {
                for (std::size_t at = first; at < last; ++at)
                    row[at] = (~length(std::uint32_t(at)) << 8) | std::uint32_t(at - first);
                std::sort(row + first, row + last);
                for (std::size_t at = first; at < last; ++at)
                    row[at] = std::uint32_t(first) + (row[at] & 0xff);
            } else {
                std::iota(row + first, row + last, std::uint32_t(first));
            }
            for (std::size_t at = first; at < last; ++at)
                place_of[row[at]] = std::uint32_t(at);
            // The last slice's lanes past n: a particle's copy (finite
            // values, g = 0 below, the results not kept).
            const std::size_t window_end = std::min(slices * slice_lanes, first + window);
            for (std::size_t at = last; at < window_end; ++at)
                row[at] = row[n - 1];
            for (std::size_t at = first; at < window_end; at += slice_lanes) {
                std::uint32_t longest = 0; // the first, when sorted
                for (std::size_t lane = at; lane < std::min(last, at + slice_lanes); ++lane)
                    longest = std::max(longest, length(row[lane]));
                columns[at / slice_lanes + 1] = longest;
            }
        }
        columns[0] = 0;
        for (std::size_t slice = 0; slice < slices; ++slice)
            columns[slice + 1] += columns[slice];
        const std::size_t entries = std::size_t(columns[slices]) * slice_lanes;
        resize_with_headroom(slice_index_, entries);
        for (std::vector<float>& component : slice_gradient_)
            resize_with_headroom(component, entries);
    }
    resize_with_headroom(wall_gradient_,
                         (context.boundary ? context.boundary_neighbours.pair_count() : 0) +
                             simd_lanes);
    // Moving walls: sum_b w_ib . v_b, fixed for the step (v_b is).
    const bool moving = context.boundary && context.boundary->has_moving();
    // Zeros when nothing moves: the solve reads it unconditionally. Read
    // under a test of a null pointer, GCC made it a masked load from
    // address 0 with every lane off, which a processor never performs but
    // qemu-user's AVX2 does (tests/portable/check_variants.sh's 3D dfsph
    // run faulted there).
    if (moving)
        wall_motion_.resize(n);
    else
        wall_motion_.assign(n, 0);
    for (std::vector<Real>& component : wall_sum_)
        component.resize(n);
    // No particle is compressed below a fraction of this: with S_i under it
    // (an isolated particle) there is nothing to push against.
    const Real tiny = 1e-9 * params.rest_density * params.rest_density / (params.h * params.h);
    // Local spans, not the members: loops that read members through `this`
    // stay scalar.
    const std::span<std::uint32_t> slice_index = slice_index_;
    std::array<float*, D> slice_gradient;
    for (int k = 0; k < D; ++k)
        slice_gradient[k] = slice_gradient_[k].data();
    const std::span<Vec<D>> wall_gradient = wall_gradient_;
    resize_with_headroom(position_f_, 4 * slices * slice_lanes);
    float* position_f = position_f_.data();
    // The same on every rank, so that a run's bits do not depend on the ranks.
    const Vec<D> origin = params.domain.min;
    const Real self = kernel_value_squared(kernel, Real(0));
    const std::uint32_t* row = slice_row_.data();
    const std::uint32_t* place_of = slice_place_.data();
    const std::uint32_t* columns = slice_start_.data();
    // A particle's walls and its results, once its fluid pairs are summed:
    // kernel_sum = sum_j W_ij, sum = sum_j g_ij, squares = sum_j |g_ij|^2.
    const auto finish = [&](std::size_t place, Real kernel_sum, const Vec<D>& sum, Real squares) {
        const std::size_t i = row[place];
        const Vec<D> x_i = state.position[i];
        const Kernel local_kernel = kernel;
        for (int k = 0; k < D; ++k)
            position_f[4 * place + k] = float(x_i[k] - origin[k]);
        Vec<D> walls_sum(0);
        Real wall_kernel_sum = 0; // sum_b V_b W_ib
        if (context.boundary) {
            const auto xb = context.boundary->positions();
            const auto volume = context.boundary->volumes();
            const auto wall_velocity = context.boundary->velocities();
            const NeighbourList& walls = context.boundary_neighbours;
            const std::size_t wall_begin = walls.start[i], wall_end = walls.start[i + 1];
            const std::uint32_t* wall_index = walls.index.data();
            const Real rho0 = params.rest_density;
            // A local copy: through the closure GCC 12 keeps the loop scalar.
            const std::span<Vec<D>> gradient = wall_gradient;
#pragma omp simd reduction(+ : wall_kernel_sum)
            for (std::size_t e = wall_begin; e < wall_end; ++e) {
                const std::uint32_t b = wall_index[e];
                const Vec<D> x_ib = x_i - xb[b];
                const Real r2 = squared_length<D>(x_ib);
                const Vec<D> w =
                    rho0 * volume[b] * boundary_gradient(local_kernel, x_ib, std::sqrt(r2));
                // Component by component: a whole vector assigned is a copy
                // through memory that keeps the loop scalar (GCC 12).
                for (int k = 0; k < D; ++k)
                    gradient[e][k] = w[k];
                wall_kernel_sum += volume[b] * kernel_value_squared(local_kernel, r2);
            }
            walls_sum =
                sum_over_pairs(walls, i, [&](std::size_t e, std::uint32_t) { return gradient[e]; });
            if (moving)
                wall_motion_[place] = sum_over_pairs(walls, i, [&](std::size_t e, std::uint32_t b) {
                    return glm::dot(gradient[e], wall_velocity[b]);
                });
        }
        for (int k = 0; k < D; ++k)
            wall_sum_[k][place] = walls_sum[k];
        // S_i = |G_f + 2 G_w|^2 + sum |g|^2 (the walls mirrored, above).
        const Vec<D> G = sum + wall_mirror * walls_sum;
        const Real S = glm::dot(G, G) + squares;
        factor_[place] = S > tiny ? 1 / S : 0;
        if (summed)
            state.density[i] =
                params.mass * (self + kernel_sum) + params.rest_density * wall_kernel_sum;
        position_f[4 * place + 3] = float(state.density[i]);
    };
    if constexpr (requires { typename Kernel::Single; }) {
        // A slice at a time, its particles' rows side by side, one to a
        // lane: column c of the slice is the lanes' c-th pairs, written
        // whole, and each lane sums its own row (in its order: the same
        // bits for any thread count). x_ij, r, W_ij and the sums in double;
        // g_ij's kernel in floats, as the iterations read g_ij. Against a
        // particle at a time (a vectorised loop over its row, then its
        // entries stored one by one), the density pass 9-12% faster on
        // SPlisHSPlasH's dam break (docs/benchmarks.md).
        const typename Kernel::Single kernel_f(Real(kernel.h));
        const float mass = float(params.mass);
        const std::uint32_t* start = context.neighbours.start.data();
        const std::uint32_t* index = context.neighbours.index.data();
        const Vec<D>* position = state.position.data();
        std::uint32_t* placed_index = slice_index.data();
        // Each thread the run of slices it takes in the solves
        // (thread_slices): it writes what its iterations then read.
#pragma omp parallel
        for (const std::size_t slice : thread_slices(columns, slices)) {
            const Kernel local_kernel = kernel;
            const std::size_t first = slice * slice_lanes;
            // Each lane's row; the lanes past n (the last slice's) have
            // none, and their own place is n - 1's.
            std::array<std::size_t, slice_lanes> begin;
            Counts length{};
            Counts own_place{}, own{};
            // (Lanes set one at a time through plain arrays: into vectors
            // GCC 12 warns of their use uninitialised.)
            double lanes_x[D][slice_lanes];
            for (std::size_t l = 0; l < slice_lanes; ++l) {
                const std::size_t place = first + l, i = row[place];
                begin[l] = start[i];
                length[l] = place < n ? start[i + 1] - start[i] : 0;
                own_place[l] = std::uint32_t(std::min(place, n - 1));
                own[l] = std::uint32_t(i);
                for (int k = 0; k < D; ++k)
                    lanes_x[k][l] = position[i][k];
            }
            std::array<Doubles, D> x_i;
            std::memcpy(x_i.data(), lanes_x, sizeof lanes_x);
            Doubles kernel_sum{}, squares{};
            std::array<Doubles, D> sum{};
            const std::uint32_t column_count = columns[slice + 1] - columns[slice];
            std::size_t at = std::size_t(columns[slice]) * slice_lanes;
            for (std::uint32_t c = 0; c < column_count; ++c, at += slice_lanes) {
                // A lane past its row's end pairs its particle with
                // itself: x_ij = 0, and g = 0 below.
                const Counts active = c < length;
                Counts placed{};
                std::array<std::uint32_t, slice_lanes> j;
                for (std::size_t l = 0; l < slice_lanes; ++l) {
                    j[l] = active[l] ? index[begin[l] + c] : own[l];
                    placed[l] = active[l] ? place_of[j[l]] : own_place[l];
                }
                std::memcpy(placed_index + at, &placed, sizeof placed);
                // r and the density's W in double: rounded to floats, a
                // change of 1e-12 m in a position could move rho by 1e-7
                // of itself, which the solves then amplify (two runs that
                // differ in their particles' order came out 20x farther
                // apart, tests/test_reorder.cpp).
                std::array<Lanes, D> x_ij;
                Doubles r2{};
                static_assert(slice_lanes == 8);
                for (int k = 0; k < D; ++k) {
                    const Doubles x_j{position[j[0]][k], position[j[1]][k], position[j[2]][k],
                                      position[j[3]][k], position[j[4]][k], position[j[5]][k],
                                      position[j[6]][k], position[j[7]][k]};
                    const Doubles x = x_i[k] - x_j;
                    x_ij[k] = __builtin_convertvector(x, Lanes);
                    r2 += x * x;
                }
                Doubles r;
                square_roots(r, r2);
                Doubles w;
                local_kernel.W_each(r, w);
                kernel_sum += __builtin_convertvector(active, Wide) ? w : Doubles{};
                Lanes dw;
                kernel_f.dW_over_r_each(__builtin_convertvector(r, Lanes), dw);
                const Lanes f = active ? mass * dw : Lanes{};
                Lanes g2{};
                for (int k = 0; k < D; ++k) {
                    const Lanes g = f * x_ij[k];
                    std::memcpy(slice_gradient[k] + at, &g, sizeof g);
                    sum[k] += __builtin_convertvector(g, Doubles);
                    g2 += g * g;
                }
                squares += __builtin_convertvector(g2, Doubles);
            }
            for (std::size_t l = 0; l < slice_lanes && first + l < n; ++l) {
                Vec<D> row_sum;
                for (int k = 0; k < D; ++k)
                    row_sum[k] = sum[k][l];
                finish(first + l, kernel_sum[l], row_sum, squares[l]);
            }
        }
    } else {
        // The seed's kernel (its gradient is not smooth at r = 0): a
        // particle at a time, in double. The last slice's lanes past n
        // first: index n - 1, g = 0 (the slices' pass above writes them).
        if (n % slice_lanes != 0) {
            const std::size_t last = slices - 1;
            for (std::size_t lane = n % slice_lanes; lane < slice_lanes; ++lane)
                for (std::size_t at = std::size_t(columns[last]) * slice_lanes + lane;
                     at < std::size_t(columns[last + 1]) * slice_lanes; at += slice_lanes) {
                    slice_index[at] = std::uint32_t(n - 1);
                    for (int k = 0; k < D; ++k)
                        slice_gradient[k][at] = 0;
                }
        }
#pragma omp parallel for schedule(dynamic, 256)
        for (std::size_t place = 0; place < n; ++place) {
            const std::size_t i = row[place];
            const NeighbourList& pairs = context.neighbours;
            const Vec<D> x_i = state.position[i];
            Real kernel_sum = 0, squares = 0;
            Vec<D> sum(0);
            const std::size_t slice = place / slice_lanes, lane = place % slice_lanes;
            std::size_t at = std::size_t(columns[slice]) * slice_lanes + lane;
            const std::size_t slice_end = std::size_t(columns[slice + 1]) * slice_lanes + lane;
            for (std::size_t e = pairs.start[i]; e < pairs.start[i + 1]; ++e, at += slice_lanes) {
                const std::uint32_t j = pairs.index[e];
                const Vec<D> x_ij = x_i - state.position[j];
                const Real r2 = squared_length<D>(x_ij);
                kernel_sum += kernel_value_squared(kernel, r2);
                const Vec<D> g =
                    params.mass * pair_gradient(kernel, state, i, j, x_ij, std::sqrt(r2));
                slice_index[at] = place_of[j];
                for (int k = 0; k < D; ++k)
                    slice_gradient[k][at] = float(g[k]);
                sum += g;
                squares += squared_length<D>(g);
            }
            // The row's padding: g = 0 (the index in cache, and valid).
            for (; at < slice_end; at += slice_lanes) {
                slice_index[at] = std::uint32_t(place);
                for (int k = 0; k < D; ++k)
                    slice_gradient[k][at] = 0;
            }
            finish(place, kernel_sum, sum, squares);
        }
    }
    timed.reset();
    // Over ranks: the halo's densities from their owners (the viscosities read them).
    if (context.halo) {
        context.share_halo_densities(state);
        for (std::size_t place = 0; place < n; ++place)
            position_f[4 * place + 3] = float(state.density[row[place]]);
    }
}

template <int D>
SPHCLIP_CLONED int DfsphSolver<D>::solve(const Params<D>& params, Real dt, Target target,
                                         StepContext<D>& context, State<D>& state) {
    const std::size_t n = state.size();
    const PressureSolveSettings& settings = params.pressure_solve;
    const Real tolerance =
        (target == Target::density ? settings.tolerance : settings.divergence_tolerance) / 100;
    const Real rho0 = params.rest_density;
    // Warm start (Bender & Koschier 2017, sec. 4.3; solver.warm_start): last
    // step's stiffness is most of this step's, so a part of it is applied
    // first and the iterations only correct the rest. Why a part
    // (solver.warm_start_fraction, 0.5 by default, as SPlisHSPlasH carries
    // it): an error in the pressure's level changes the density error only
    // in the bottom rows, so the mean a solve stops at hardly sees it (a
    // part in 80 in a column 80 rows deep). Carried whole, such an error is
    // never corrected, and a deep column bounces, its pressure alternating
    // between near zero and twice hydrostatic (33-54% RMS off); carried by
    // half, each solve rebuilds half of it and the error halves every step
    // (docs/validation.md, "The warm start carried by half";
    // tests/test_solvers.cpp). Only a particle at or above the rest
    // density carries its pressure: one short of neighbours is at the free
    // surface, where the pressure is zero, and a drop leaving the fluid with
    // its last pressure was shot off at 6.6 m/s on the water dam break (its
    // steps, set by the fastest particle, then 27% more; measured). The
    // carried density is never below rho0: there all carry. The density
    // solve's s = dt p / rho^2 scales with dt; the divergence solve
    // restarts from half its last value, since its source changes sign more
    // often.
    std::vector<Real>& sum = target == Target::density ? stiffness_sum_ : divergence_sum_;
    std::vector<Real>& previous =
        target == Target::density ? previous_stiffness_ : previous_divergence_;
    const Real scale = target == Target::divergence ? Real(0.5)
                       : previous_dt_ > 0 ? settings.warm_start_fraction * dt / previous_dt_
                                          : 0;
    // Over ranks: the halo's velocities from their owners (the kick gave
    // the halo accelerations from incomplete neighbourhoods).
    // The floats the iterations read follow: correct_velocities rounds what
    // it changes, the halo's are rounded when they arrive.
    // The solve works in the slices' order (its arrays by place, below);
    // state.velocity is written back at its end.
    const auto share_velocities = [&] {
        if (context.halo) {
            store_velocities(state);
            context.share_halo(state.velocity);
            load_velocities(state);
        }
    };
    const std::uint32_t* row = slice_row_.data();
    context.share_halo(state.velocity);
    load_velocities(state);
    velocity_at_start_ = state.velocity; // for a restart (below)
    if (settings.warm_start && previous.size() == n && scale > 0) {
#pragma omp parallel for schedule(static)
        for (std::size_t place = 0; place < n; ++place) {
            const std::size_t i = row[place];
            stiffness_[place] = state.density[i] < rho0 ? 0 : scale * previous[i];
            stiffness_f_[place] = float(stiffness_[place]);
        }
        correct_velocities(state);
        share_velocities();
        sum = stiffness_;
    } else {
        sum.assign(n, 0);
    }
    // The density solve's source less the rate, fixed for the solve.
    compression_.resize(n);
    if (target == Target::density) {
#pragma omp parallel for schedule(static)
        for (std::size_t place = 0; place < n; ++place)
            compression_[place] = (state.density[row[place]] - rho0) / dt;
    } else {
        std::fill(compression_.begin(), compression_.end(), Real(0));
    }
    const Real particles = Real(context.total_particles(n));
    // The error's sum, exact in any order: each particle's part, dt
    // residual / rho0 (at most 1 counted), rounded to whole units of
    // 2^-k, so that all the particles' parts sum below 2^52, where doubles
    // add integers exactly. So the threads sum it as they go (an OpenMP
    // reduction), and the iteration count, and every bit, is still the
    // same for any thread or rank count. Summed in particle order by one
    // thread, as until 2026-12-07, it was a wait for the others at every
    // iteration (about 1% of SPlisHSPlasH's dam break, measured); a unit
    // of 2^-39 (6,859 particles) moves the mean error by under 1e-12.
    int bits = 0;
    while (std::ldexp(Real(1), bits) < particles)
        ++bits;
    const Real units = std::ldexp(Real(1), 52 - bits);
    const std::size_t owned_begin = context.halo ? context.halo->owned_begin() : 0;
    const std::size_t owned_end = context.halo ? context.halo->owned_end() : n;
    // A diverging iteration (the error grows instead of shrinking: particles
    // stacked on each other make the system far from diagonally dominant) is
    // restarted from the solve's start with half the relaxation, a few times;
    // the watchdog judges what comes out if that still fails.
    Real omega = jacobi_relaxation;
    Real first_error = -1;
    int restarts = 0;
    int iterations = 0;
    for (;;) {
        // Local pointers for what the per-particle loop reads (through
        // `this` GCC 12 keeps a loop scalar).
        std::array<const Real*, D> wall_sum, velocity;
        for (int k = 0; k < D; ++k) {
            wall_sum[k] = wall_sum_[k].data();
            velocity[k] = placed_velocity_[k].data();
        }
        const Real* wall_motion = wall_motion_.data();
        const Real* compression = compression_.data();
        const Real* factor = factor_.data();
        const Real* summed = sum.data();
        Real* stiffness = stiffness_.data();
        Real* next_sum = next_sum_.data();
        Real* source_of = source_.data();
        float* stiffness_f = stiffness_f_.data();
        const SliceView slices = slice_view();
        // stiffness_ holds each particle's last step from the second pass
        // of a solve (or of a restart) on; before, the warm start's.
        const Real momentum = iterations > 0 && first_error >= 0 ? settings.momentum : Real(0);
        const Real relaxation = omega;
        // The compression rate with the current velocities, and the source
        // each particle's stiffness answers: the predicted density error
        // (density solve) or the rate itself (divergence solve).
        Real counted = 0; // the error's sum, in units (above)
#pragma omp parallel reduction(+ : counted)
        for (const std::size_t slice : thread_slices(slices.columns, slice_count(n))) {
            // sum_j g_ij . (v_i - v_j) for the slice's particles, one a lane,
            // component by component.
            const std::size_t first = slice * slice_lanes;
            std::array<Lanes, 4> v_i;
            load_quads(v_i, slices.velocity, first);
            std::array<Lanes, D> pair_sum{};
            for (std::size_t at = slices.first_entry(slice), end = slices.end_entry(slice);
                 at < end; at += slice_lanes) {
                std::array<Lanes, 4> v_j;
                gather_quads(v_j, slices.velocity, slices.index + at);
                for (int k = 0; k < D; ++k) {
                    Lanes g;
                    load_lanes(g, slices.gradient[k] + at);
                    pair_sum[k] += g * (v_i[k] - v_j[k]);
                }
            }
            Lanes pair_rate = pair_sum[0];
            for (int k = 1; k < D; ++k)
                pair_rate += pair_sum[k];
            // The slice's particles, lane by lane in doubles (in a vector:
            // their arrays are in the slices' order).
            const std::size_t lanes = std::min(slice_lanes, n - first);
            Real slice_counted = 0;
            // The thread's own copies of the pointers: through the shared
            // ones GCC read every W_i and v_i by a gather.
            const std::array<const Real*, D> w = wall_sum, v = velocity;
#pragma omp simd reduction(+ : slice_counted)
            for (std::size_t lane = 0; lane < lanes; ++lane) {
                const std::size_t place = first + lane;
                Real walls = 0;
                for (int k = 0; k < D; ++k)
                    walls += w[k][place] * v[k][place];
                Real rate = wall_mirror * walls + Real(pair_rate[lane]);
                rate -= wall_mirror * wall_motion[place]; // 0 without moving walls
                const Real source = compression[place] + rate;
                source_of[place] = source;
                // The residual of a pressure that must stay >= 0: compression
                // anywhere, and expansion where there is pressure to give back;
                // its part in the error in whole units, the owned particles'.
                const Real residual =
                    summed[place] > 0 ? std::abs(source) : std::max(source, Real(0));
                const bool owned = row[place] >= owned_begin && row[place] < owned_end;
                slice_counted +=
                    owned ? std::nearbyint(std::min(residual * dt / rho0, Real(1)) * units) : 0;
                // Relaxed, projected Jacobi. Relaxed: the plain Jacobi update
                // (the factor ignores how neighbours respond) overshoots and,
                // with the 20-40 neighbours of our kernels, diverges in a deep
                // tank; half of it converges, as in IISPH (Ihmsen et al. 2014,
                // omega = 0.5). Projected: the summed stiffness (a pressure)
                // never goes below zero, so the fluid does not pull itself
                // together, but an expanding particle gives back pressure it was
                // given before, which the warm start would otherwise only ever
                // add to. Computed here, in the same pass (one fewer over the
                // particles and one fewer wait for the threads an iteration), and
                // taken below unless the solve stops.
                // With momentum (Polyak's heavy ball, 1964; solver.momentum,
                // 0 by default): the step also carries a part of the
                // particle's last one, which the slow, smooth part of the
                // error (a column's pressure level) keeps asking for step
                // after step: 0.5 took 1.7x fewer density iterations on
                // SPlisHSPlasH's dam break, but its fastest particles ran
                // 15% faster and a tank's pressure came out less exact
                // (docs/solvers.md). Only while the two agree in sign: a
                // particle that overshot starts afresh (as adaptive restarts
                // do, O'Donoghue & Candes 2015); carried regardless, an
                // emitter's inflow stacked particles to 0.29 spacings
                // (tests/test_effects.cpp). In the density solve alone, a
                // deep 3D tank at rest sloshed at 1.5 m/s.
                const Real step = relaxation * source * factor[place];
                const Real carried =
                    step * stiffness[place] > 0 ? momentum * stiffness[place] : Real(0);
                const Real updated = std::max(summed[place] + step + carried, Real(0));
                stiffness[place] = updated - summed[place];
                stiffness_f[place] = float(stiffness[place]);
                next_sum[place] = updated;
            }
            counted += slice_counted;
        }
        // Over ranks, continued from rank to rank (exact as well).
        if (context.halo)
            counted = context.halo->finish_sum(context.halo->sum_before() + counted);
        // Mean relative density error (density) or density change within one
        // step (divergence): dt * mean(residual) / rho0 in both cases.
        const Real error = particles > 0 ? counted / units / particles : 0;
        if (target == Target::density)
            last_density_error_pct_ = 100 * error;
        if (first_error < 0) {
            first_error = error;
        } else if (error > 2 * first_error && error > tolerance && restarts < 4 &&
                   iterations < settings.max_iterations) {
            state.velocity = velocity_at_start_;
            load_velocities(state);
            sum.assign(n, 0);
            omega /= 2;
            first_error = -1;
            ++restarts;
            continue;
        }
        const bool converged = error <= tolerance && iterations >= settings.min_iterations;
        if (converged || iterations >= settings.max_iterations)
            break;
        sum.swap(next_sum_);
        // Over ranks the halo's stiffnesses, then its corrected velocities,
        // are their owners' (a halo particle's own source is incomplete).
        if (context.halo) {
            halo_scratch_.resize(n);
            for (std::size_t place = 0; place < n; ++place)
                halo_scratch_[row[place]] = stiffness_[place];
            context.share_halo(halo_scratch_);
            for (std::size_t place = 0; place < n; ++place) {
                stiffness_[place] = halo_scratch_[row[place]];
                stiffness_f_[place] = float(stiffness_[place]);
            }
        }
        correct_velocities(state);
        share_velocities();
        ++iterations;
    }
    // Back in the particles' order.
    store_velocities(state);
    previous.resize(n);
#pragma omp parallel for schedule(static)
    for (std::size_t place = 0; place < n; ++place)
        previous[row[place]] = sum[place];
    return iterations;
}

// dv_i = - sum_j (s_i + s_j) g_ij - sum_b 2 s_i w_ib with s = stiffness_:
// a wall particle takes the stiffness (the pressure) of the fluid particle
// beside it, so the walls, several layers of fluid-like particles, hold the
// fluid up as the fluid below would (a single-sided s_i, as for Akinci's one
// layer, leaves the bottom layer at twice the hydrostatic pressure).
// Gather: each particle corrects only its own velocity.
template <int D>
SPHCLIP_CLONED void DfsphSolver<D>::correct_velocities(const State<D>& state) {
    const std::size_t n = state.size();
    std::array<const Real*, D> wall_sum;
    std::array<Real*, D> velocity; // written here, with its floats
    for (int k = 0; k < D; ++k) {
        wall_sum[k] = wall_sum_[k].data();
        velocity[k] = placed_velocity_[k].data();
    }
    const Real* stiffness = stiffness_.data();
    const float* stiffness_f = stiffness_f_.data();
    const SliceView slices = slice_view();
    float* velocity_f = velocity_f_.data();
#pragma omp parallel
    for (const std::size_t slice : thread_slices(slices.columns, slice_count(n))) {
        // sum_j (s_i + s_j) g_ij for the slice's particles, one a lane.
        const std::size_t first = slice * slice_lanes;
        Lanes s_i;
        load_lanes(s_i, stiffness_f + first);
        std::array<Lanes, D> pair_sum{};
        for (std::size_t at = slices.first_entry(slice), end = slices.end_entry(slice); at < end;
             at += slice_lanes) {
            Lanes s_j;
            gather_lanes(s_j, stiffness_f, slices.index + at);
            const Lanes s_ij = s_i + s_j;
            for (int k = 0; k < D; ++k) {
                Lanes g;
                load_lanes(g, slices.gradient[k] + at);
                pair_sum[k] += s_ij * g;
            }
        }
        // Out of the registers once (read lane by lane from the vectors
        // themselves, GCC stored them to memory at every column).
        std::array<std::array<float, slice_lanes>, D> pairs;
        std::memcpy(pairs.data(), pair_sum.data(), sizeof pairs);
        const std::size_t lanes = std::min(slice_lanes, n - first);
#pragma omp simd
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            const std::size_t place = first + lane;
            for (int k = 0; k < D; ++k) {
                const Real dv =
                    wall_mirror * stiffness[place] * wall_sum[k][place] + Real(pairs[k][lane]);
                velocity[k][place] -= dv;
                velocity_f[4 * place + k] = float(velocity[k][place]);
            }
        }
    }
}

// Monaghan's and Morris's viscosities between fluid particles, as in
// pressure_acceleration.hpp (with no pressure), over the slices:
//   a_i += -sum_j Pi_ij g_ij + (2 mu / rho_i) sum_j (x_ij . g_ij) / (rho_j (r^2 + eps)) v_ij
// with g_ij = m grad W_ij as the solves use it, in floats: positions as
// offsets from the domain's corner (a domain far from the origin loses nothing),
// the velocities the divergence solve left.
template <int D>
template <bool artificial, bool laminar>
SPHCLIP_CLONED void DfsphSolver<D>::add_fluid_viscosities(const MonaghanTerm<float>& Pi,
                                                          const MorrisViscosity::Single& morris,
                                                          State<D>& state) const {
    const std::size_t n = state.size();
    const SliceView slices = slice_view();
    const float* position_f = position_f_.data();
#pragma omp parallel
    for (const std::size_t slice : thread_slices(slices.columns, slice_count(n))) {
        const std::size_t first = slice * slice_lanes;
        // (x_i, rho_i) and v_i, one a lane.
        std::array<Lanes, 4> x_i, v_i;
        load_quads(x_i, position_f, first);
        load_quads(v_i, slices.velocity, first);
        const Lanes rho_i = x_i[3];
        std::array<Lanes, D> along_g{}, along_v{};
        for (std::size_t at = slices.first_entry(slice), end = slices.end_entry(slice); at < end;
             at += slice_lanes) {
            std::array<Lanes, 4> x_j, v_j;
            gather_quads(x_j, position_f, slices.index + at);
            gather_quads(v_j, slices.velocity, slices.index + at);
            const Lanes rho_j = x_j[3];
            std::array<Lanes, D> x_ij, v_ij, g;
            Lanes r2{}, v_dot_x{}, x_dot_g{};
            for (int k = 0; k < D; ++k) {
                x_ij[k] = x_i[k] - x_j[k];
                v_ij[k] = v_i[k] - v_j[k];
                load_lanes(g[k], slices.gradient[k] + at);
                r2 += x_ij[k] * x_ij[k];
                v_dot_x += v_ij[k] * x_ij[k];
                x_dot_g += x_ij[k] * g[k];
            }
            if constexpr (artificial) {
                Lanes Pi_ij;
                Pi(v_dot_x, rho_i + rho_j, r2, Pi_ij);
                for (int k = 0; k < D; ++k)
                    along_g[k] += Pi_ij * g[k];
            }
            if constexpr (laminar) {
                // The padding's g = 0 makes its x . g 0 (and r^2 + eps > 0).
                const Lanes weight = x_dot_g / (rho_j * (r2 + morris.eps));
                for (int k = 0; k < D; ++k)
                    along_v[k] += weight * v_ij[k];
            }
        }
        for (std::size_t lane = 0; lane < slice_lanes && first + lane < n; ++lane) {
            const std::size_t i = slices.row[first + lane];
            const Real viscous_scale = laminar ? morris.two_mu / state.density[i] : 0;
            for (int k = 0; k < D; ++k)
                state.acceleration[i][k] +=
                    -Real(along_g[k][lane]) + viscous_scale * Real(along_v[k][lane]);
        }
    }
}

// The walls' pressure with its hydrostatic rise (solver.wall_pressure):
// p_b = max(p_i + rho_i g . (x_b - x_i), 0), Adami et al. 2012's eq. 27
// taken pair by pair: the fluid's hydrostatic pressure continued into the
// wall, higher below the particle and lower above it, never below zero (a
// wall does not pull). The mirrored part is the solves' 2 s_i
// (correct_velocities); the rise does not depend on the solve, so it is a
// force known before it, a_i = -sum_b rho0 V_b (p_b - p_i) / rho_i^2 grad W_ib,
// and the density solve then removes what it still compresses. The floor
// at zero needs p_i, which this step's solve has not found yet: the last
// density solve's stands in for it (the same at rest; zero at the first
// step).
// Both sides matter: beside a side wall the rise below and the fall above
// together hold the fluid up as the fluid beyond would; the rise alone
// (the walls below only) held it half as much and pushed it off the wall
// with a force that changes with height, which stirred the 3D tank at
// 1-2 cm/s (docs/validation.md, "The 3D tank at rest").
template <int D>
void DfsphSolver<D>::add_wall_weight(const Params<D>& params, const StepContext<D>& context,
                                     State<D>& state) const {
    const std::size_t n = state.size();
    const NeighbourList& walls = context.boundary_neighbours;
    const auto xb = context.boundary->positions();
    const std::span<const Vec<D>> wall_gradient = wall_gradient_;
    const Vec<D> g = params.wall_gravity;
    // p_i / rho_i = rho_i s_i / dt of the last density solve, where there is one.
    const bool known = previous_dt_ > 0 && previous_stiffness_.size() == n;
    const std::span<const Real> stiffness = previous_stiffness_;
    const Real last_dt = previous_dt_;
#pragma omp parallel for schedule(dynamic, 256)
    for (std::size_t i = 0; i < n; ++i) {
        const Vec<D> x_i = state.position[i];
        const Real p_over_rho = known ? state.density[i] * stiffness[i] / last_dt : 0;
        const Vec<D> a = sum_over_pairs(walls, i, [&](std::size_t e, std::uint32_t b) {
            return std::max(-glm::dot(g, x_i - xb[b]), -p_over_rho) * wall_gradient[e];
        });
        state.acceleration[i] -= a / state.density[i];
    }
}

// A step whose density solve ends at solver.max_iterations above its
// tolerance is not incompressible: the compression it leaves springs back
// later (measured: a column at rest, whose first step takes dt_max and must
// build the whole hydrostatic pressure from zero, left 21% at its base at
// a / 80 and shot its bottom rows along the floor at 3.5 m/s). The
// compression a step adds grows as dt^2 (g dt^2 at rest), so such a step,
// when it started within the tolerance, asks to be redone as two halves
// (Simulation::take_step), up to max_splits times. The halves are one
// step in stats.csv's `steps`; their iterations, the failed attempt's
// included, are in its pressure and divergence iterations.
template <int D>
StepReport DfsphSolver<D>::step(const Params<D>& params, Real dt, State<D>& state,
                                StepContext<D>& context) {
    StepReport report;
    const bool may_split = context.halvings < max_splits;
    if (may_split)
        velocity_at_step_start_ = state.velocity; // reused memory once sizes settle
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        // 1. Neighbours, density (fluid + walls), the factors alpha_i.
        prepare(params, kernel, context, state);
        // 2. Divergence-free velocities (the previous step's end, Algorithm 1 line 12).
        {
            auto timed = context.time(Stage::divergence_solve);
            report.divergence_iterations = solve(params, dt, Target::divergence, context, state);
        }
    });
    // Halving helps only with the compression this step adds (g dt^2); a
    // compression the step starts with needs the same iterations at any dt,
    // and removing it in a shorter step takes faster corrections (measured:
    // a paddle's channel blew up). So a step is split only when it starts
    // within the tolerance. Summed in particle order: the same bits for any
    // thread or rank count.
    Real compression_at_start_pct = 0;
    if (may_split) {
        const std::size_t n = state.size();
        const Real sum = context.sum_in_particle_order(n, [&](std::size_t i) {
            return std::max(state.density[i] - params.rest_density, Real(0));
        });
        const Real particles = Real(context.total_particles(n));
        compression_at_start_pct =
            particles > 0 ? 100 * sum / (particles * params.rest_density) : 0;
    }
    // 3. Non-pressure forces, the scene's effects (viscosity, gravity, ...); v* = v + dt a.
    // Monaghan's and Morris's viscosities, when the scene names them, in
    // one pass over the pairs (pressure_acceleration.hpp, with no pressure).
    const auto* artificial = fused_effect<ArtificialViscosity<D>>(context.effects);
    const auto* laminar = fused_effect<LaminarViscosity<D>>(context.effects);
    if (artificial || laminar) {
        auto timed = context.time(Stage::viscosities);
        const MonaghanViscosity monaghan =
            artificial ? artificial->pair_viscosity(params) : MonaghanViscosity{};
        const MorrisViscosity morris =
            laminar ? laminar->pair_viscosity(params) : MorrisViscosity{};
        const PairViscosities viscosities{artificial ? &monaghan : nullptr,
                                          laminar ? &morris : nullptr};
        // The walls' terms over their pairs, then the fluid pairs' in the
        // slices, in floats.
        viscosities.dispatch([&](auto has_artificial, auto has_laminar) {
            constexpr bool with_artificial = decltype(has_artificial)::value;
            constexpr bool with_laminar = decltype(has_laminar)::value;
            if (context.boundary)
                set_wall_viscosities<with_artificial, with_laminar>(
                    params, viscosities, *context.boundary, context.boundary_neighbours,
                    wall_gradient_, state);
            else
                std::fill(state.acceleration.begin(), state.acceleration.end(), Vec<D>(0));
            add_fluid_viscosities<with_artificial, with_laminar>(monaghan.single(), morris.single(),
                                                                 state);
        });
    } else {
        std::fill(state.acceleration.begin(), state.acceleration.end(), Vec<D>(0));
    }
    const std::array<const Effect<D>*, 2> merged{artificial, laminar};
    context.apply_effects(params, state, merged, Stage::viscosities);
    if (params.wall_gravity != Vec<D>(0) && context.boundary) {
        auto timed = context.time(Stage::pressure_solve);
        add_wall_weight(params, context, state);
    }
    {
        auto timed = context.time(Stage::integration);
        kick(dt, state);
    }
    // 4. Constant density: v so that rho* = rho0; p_i = rho_i^2 s_i / dt.
    auto solve_timed = std::make_optional<StageTimes::Scope>(context.stages, Stage::pressure_solve);
    report.pressure_iterations = solve(params, dt, Target::density, context, state);
    solve_timed.reset();
    if (may_split && report.pressure_iterations >= params.pressure_solve.max_iterations &&
        last_density_error_pct_ > params.pressure_solve.tolerance &&
        compression_at_start_pct <= params.pressure_solve.tolerance) {
        // Not converged: back to the step's start, to be taken in two halves.
        state.velocity = velocity_at_step_start_;
        report.redo_in_halves = true;
        return report;
    }
    // The pressure itself moves nothing (the solves work with stiffnesses):
    // it is an output, computed only when one reads it.
    if (context.output_pressure) {
        auto timed = context.time(Stage::pressure_solve);
        const std::size_t n = state.size();
        const std::uint32_t* row = slice_row_.data();
#pragma omp parallel for schedule(static)
        for (std::size_t place = 0; place < n; ++place) {
            const std::size_t i = row[place];
            state.pressure[i] = state.density[i] * state.density[i] *
                                (stiffness_sum_[place] + divergence_sum_[place]) / dt;
        }
    }
    // solver.density = carried: the continuity equation over the step
    // (after the pressure output, which is in this step's density),
    // rho += dt D rho / Dt with the velocities the density solve ended with,
    // which is the density it predicted, rho0 + dt * source.
    if (params.density_model == DensityModel::carried) {
        auto timed = context.time(Stage::pressure_solve);
        const std::size_t n = state.size();
        const Real rho0 = params.rest_density;
        const std::uint32_t* row = slice_row_.data();
#pragma omp parallel for schedule(static)
        for (std::size_t place = 0; place < n; ++place)
            state.density[row[place]] = rho0 + dt * source_[place];
    }
    previous_dt_ = dt;
    // 5. Move; the boundaries keep the particles out as a last guard, behind
    // the boundary particles.
    {
        auto timed = context.time(Stage::integration);
        drift(dt, state);
    }
    report.obstacle_pushes = context.last_guard(context.start_time + dt, state);
    return report;
}

template <int D>
void DfsphSolver<D>::update_fields(const Params<D>& params, State<D>& state,
                                   StepContext<D>& context) {
    // Density at the current positions (or the carried one); pressure stays
    // the last solve's.
    with_kernel<D>(kernel_, params.h, [&](const auto& kernel) {
        if (params.density_model == DensityModel::carried)
            find_neighbours_and_carried_density(params, kernel, context, state);
        else
            find_neighbours_and_density(params, kernel, context, state);
    });
}

template class DfsphSolver<2>;
template class DfsphSolver<3>;

} // namespace sph
