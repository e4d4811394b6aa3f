#include "parallel/rank_partition.hpp"

#include "parallel/world.hpp"
#include "scene/input_error.hpp"
#include "sph/effects/surface_tension.hpp"
#include "sph/solvers/explicit_solver.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mpi.h>
#include <omp.h>
#include <stdexcept>
#include <vector>

namespace sph::parallel {

namespace {

// Coarse cells at most per particle for the halo's grid; a box sparser
// than that (a far stray particle) puts every particle in the halo, which
// is exact, only slower.
constexpr std::size_t max_cells_per_particle = 64;
// After each rank's results in the gather: its owned + halo count, its
// solver seconds, the halo bytes it received and which of the solver's kept
// arrays it filled (a bit each), so the balance and the traffic are measured
// without another message.
constexpr std::size_t trailer = 4;
// Point-to-point tags: a rank's halo request (the particles it needs from
// an owner), each exchange of their values in the step, and a sum in
// particle order passed on to the next rank.
constexpr int request_tag = 24;
constexpr int values_tag = 25;
constexpr int sum_tag = 26;
// Halo cells per reach along an axis: the halo is the owned particles' cells
// grown by this many cells, so it holds particles up to (1 + 1 / 3) reach
// away rather than 2 reaches with cells as large as the reach.
constexpr int halo_subdivision = 3;

template <int D>
class RankPartition final : public Partition<D>, public HaloExchange<D> {
  public:
    RankPartition(int hops, bool whole_cells)
        : hops_(hops), whole_cells_(whole_cells), rank_(rank()), ranks_(size()) {
        const auto p = std::size_t(ranks_);
        need_.assign(p, 0);
        need_first_.assign(p, 0);
        give_.assign(p, 0);
        give_first_.assign(p + 1, 0);
        first_.resize(std::size_t(ranks_) + 1);
        counts_.resize(std::size_t(ranks_));
        displacements_.resize(std::size_t(ranks_));
        last_local_.assign(std::size_t(ranks_), 0);
        last_owned_.assign(std::size_t(ranks_), 0);
    }

    StepReport step(Solver<D>& solver, const Params<D>& params, Real dt, State<D>& state,
                    StepContext<D>& context) override {
        const std::size_t n = state.size();
        cut(n);
        // The accelerations a Verlet step reuses are the whole state's: as
        // current as on one rank, whatever subset this step holds. When they
        // are not (the first step, new particles), the step computes them
        // before it drifts by them: nothing bounds that drift beforehand, so
        // this step holds every particle.
        const bool current = stepped_ && n == stepped_size_;
        {
            auto timed = context.time(Stage::rank_halo);
            select_local(params, dt, state, params.integrator == Integrator::verlet && !current);
            plan_halo();
            copy_local(state);
        }
        if (auto* explicit_solver = dynamic_cast<ExplicitSolver<D>*>(&solver))
            explicit_solver->set_accelerations_current(current, local_.size());
        const std::span<std::vector<Real>* const> kept = solver.kept_arrays();
        localise_kept(kept);
        const auto start = std::chrono::steady_clock::now();
        // A rank that owns nothing (fewer particles than ranks) steps an
        // empty state: it holds no halo, so no rank exchanges with it, but
        // it takes part in the solves' sums over all particles (dfsph).
        context.halo = this;
        StepReport report = solver.step(params, dt, local_, context);
        context.halo = nullptr;
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stepped_ = true;
        stepped_size_ = n;
        {
            auto timed = context.time(Stage::rank_gather);
            share_results(state, seconds, kept);
        }
        // Each rank's pushes, halo included: a particle near a rank's edge is
        // pushed on every rank that holds it (docs/mpi.md).
        std::uint64_t pushes = 0;
        MPI_Allreduce(&report.obstacle_pushes, &pushes, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
        report.obstacle_pushes = pushes;
        return report;
    }

    // The halo's densities and pressures from their owners, point to point
    // (non-blocking): each rank sends its owned particles that another
    // rank's halo holds, as that rank asked in plan_halo().
    void share_densities(State<D>& state) override {
        exchange(
            2,
            [&](std::size_t k, Real* out) {
                out[0] = state.density[k];
                out[1] = state.pressure[k];
            },
            [&](std::size_t j, const Real* in) {
                state.density[j] = in[0];
                state.pressure[j] = in[1];
            });
    }

    // An iterative solve's values (dfsph's stiffnesses and velocities, each
    // iteration), the same way.
    void share(std::span<Real> values) override {
        const auto start = std::chrono::steady_clock::now();
        exchange(
            1, [&](std::size_t k, Real* out) { out[0] = values[k]; },
            [&](std::size_t j, const Real* in) { values[j] = in[0]; });
        solve_exchange_seconds_ += seconds_since(start);
    }
    void share(std::span<Vec<D>> values) override {
        const auto start = std::chrono::steady_clock::now();
        exchange(
            D,
            [&](std::size_t k, Real* out) {
                for (int a = 0; a < D; ++a)
                    out[a] = values[k][a];
            },
            [&](std::size_t j, const Real* in) {
                for (int a = 0; a < D; ++a)
                    values[j][a] = in[a];
            });
        solve_exchange_seconds_ += seconds_since(start);
    }

    std::size_t owned_begin() const override { return owned_offset_; }
    std::size_t owned_end() const override { return owned_offset_ + owned_in_local_; }
    std::size_t total_particles() const override { return first_[std::size_t(ranks_)]; }

    // A sum in particle order: the ranges follow the memory order, so rank
    // r continues the sum of ranks 0 .. r - 1 and passes it on; the last
    // rank's is the whole sum, the same bits as one process's. The ranks
    // add one after the other, N additions in all, as one process does.
    Real sum_before() override {
        sum_start_ = std::chrono::steady_clock::now();
        Real sum = 0;
        if (rank_ > 0)
            MPI_Recv(&sum, 1, MPI_DOUBLE, rank_ - 1, sum_tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        return sum;
    }
    Real finish_sum(Real sum) override {
        if (rank_ + 1 < ranks_)
            MPI_Send(&sum, 1, MPI_DOUBLE, rank_ + 1, sum_tag, MPI_COMM_WORLD);
        MPI_Bcast(&sum, 1, MPI_DOUBLE, ranks_ - 1, MPI_COMM_WORLD);
        solve_exchange_seconds_ += seconds_since(sum_start_);
        ++sums_;
        return sum;
    }

    nlohmann::json report() const override {
        const double steps = std::max<double>(double(steps_), 1);
        return {
            {"ranks", ranks_},
            {"threads_per_rank", omp_get_max_threads()},
            {"decomposition",
             "contiguous ranges of the sorted grid's cell order (Morton curve), cut by particle "
             "count every step; whole state on every rank; each rank steps its own particles and "
             "a halo, whose densities its owners send point to point mid-step; owned results "
             "all-gathered"},
            {"halo_support_radii", hops_},
            {"halo_bytes_received_per_step", halo_bytes_ / steps / ranks_},
            // dfsph: its iterations' exchanges and sums in particle order
            // (rank 0's time in them, waiting included).
            {"solve_exchange_seconds", solve_exchange_seconds_},
            {"sums_in_particle_order", sums_},
            {"steps", steps_},
            {"owned_per_rank", last_owned_},
            {"owned_and_halo_per_rank", last_local_},
            {"imbalance",
             {{"particles_mean", work_imbalance_sum_ / steps},
              {"particles_max", work_imbalance_max_},
              {"seconds_mean", time_imbalance_sum_ / steps},
              {"seconds_max", time_imbalance_max_}}},
            {"halo_particles_per_step", double(halo_sum_) / steps},
            {"gather_bytes_received_per_step", double(received_bytes_) / steps},
            {"bytes_received_per_step",
             halo_bytes_ / steps / ranks_ + double(received_bytes_) / steps},
            {"gather_bytes_received", received_bytes_},
            {"migration_bytes_per_step", 0},
            {"migrations", migrations_},
            {"most_ranks_visited", most_visited_},
            {"steps_with_an_empty_rank", steps_with_empty_rank_},
        };
    }

    // The whole state's kept arrays follow the reorder as the solver's own
    // do in one process.
    void permute(std::span<const std::uint32_t> order) override {
        for (std::vector<Real>& whole : kept_whole_)
            if (whole.size() == order.size())
                sph::permute(whole, order, permute_scratch_);
    }

  private:
    // Per particle in the gather: x, v, a, rho, p, then the solver's kept arrays.
    static constexpr std::size_t state_stride = 3 * D + 2;

    static double seconds_since(std::chrono::steady_clock::time_point start) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    // Values of the owned particles that other ranks' halos hold, `width`
    // a particle: pack(k, out) writes local particle k's, unpack(j, in)
    // stores halo particle j's from its owner.
    template <class Pack, class Unpack>
    void exchange(std::size_t width, Pack pack, Unpack unpack) {
        const auto p = std::size_t(ranks_);
        give_values_.resize(width * give_index_.size());
        for (std::size_t k = 0; k < give_index_.size(); ++k)
            pack(give_index_[k], give_values_.data() + width * k);
        need_values_.resize(width * (local_.size() - owned_in_local_));
        requests_.clear();
        std::size_t at = 0;
        for (std::size_t s = 0; s < p; ++s) {
            if (need_[s] == 0)
                continue;
            requests_.emplace_back();
            MPI_Irecv(need_values_.data() + at, int(width * std::size_t(need_[s])), MPI_DOUBLE,
                      int(s), values_tag, MPI_COMM_WORLD, &requests_.back());
            at += width * std::size_t(need_[s]);
        }
        for (std::size_t r = 0; r < p; ++r) {
            if (give_[r] == 0)
                continue;
            requests_.emplace_back();
            MPI_Isend(give_values_.data() + width * give_first_[r],
                      int(width * std::size_t(give_[r])), MPI_DOUBLE, int(r), values_tag,
                      MPI_COMM_WORLD, &requests_.back());
        }
        MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
        at = 0;
        for (std::size_t s = 0; s < p; ++s)
            for (int k = 0; k < need_[s]; ++k, at += width)
                unpack(need_first_[s] + std::size_t(k), need_values_.data() + at);
        step_halo_bytes_ += double(at * sizeof(Real));
    }

    // The solver's kept arrays for the particles this step holds, from the
    // whole state's; empty where the whole state has none (the first step,
    // new particles), as the solver's own would be in one process.
    void localise_kept(std::span<std::vector<Real>* const> kept) {
        kept_whole_.resize(kept.size());
        for (std::size_t a = 0; a < kept.size(); ++a) {
            std::vector<Real>& local = *kept[a];
            const std::vector<Real>& whole = kept_whole_[a];
            if (whole.size() != first_[std::size_t(ranks_)]) {
                local.clear();
                continue;
            }
            local.resize(local_index_.size());
            for (std::size_t k = 0; k < local_index_.size(); ++k)
                local[k] = whole[local_index_[k]];
        }
    }

    // Rank r owns [first_[r], first_[r + 1]).
    void cut(std::size_t n) {
        for (int r = 0; r <= ranks_; ++r)
            first_[std::size_t(r)] =
                std::size_t(std::uint64_t(n) * std::uint64_t(r) / std::uint64_t(ranks_));
    }

    // local_index_: the owned particles and those within the halo's reach
    // of one, by ascending memory position (so the owned ones are one run).
    void select_local(const Params<D>& params, Real dt, const State<D>& state, bool everyone) {
        const std::size_t n = state.size();
        const std::size_t begin = first_[std::size_t(rank_)], end = first_[std::size_t(rank_) + 1];
        // How far a Verlet step moves a particle before its forces (half-kick,
        // then drift) widens every link of the chain, at both ends. The other
        // steps (symplectic Euler; dfsph, whose redone halves are steps of
        // their own) find every neighbour where the particles are at their
        // start and move them only at their end: no allowance.
        Real move = 0;
        if (params.integrator == Integrator::verlet) {
            Real v2_max = 0, a2_max = 0;
            for (std::size_t i = 0; i < n; ++i) {
                v2_max = std::max(v2_max, squared_length<D>(state.velocity[i]));
                a2_max = std::max(a2_max, squared_length<D>(state.acceleration[i]));
            }
            move = dt * std::sqrt(v2_max) + dt * dt * std::sqrt(a2_max);
        }
        // The float passes (solver.precision single) sum over every particle
        // of the 3^D cells around a particle's cell, a lane per candidate:
        // the same bits need the same candidates, every particle of the
        // cells within `hops` cells of an owned one's, so one cell further.
        const Real reach =
            Real(hops_ + (whole_cells_ ? 1 : 0)) * (params.h * (1 + 1e-5) + 2 * move) * (1 + 1e-6);
        local_index_.clear();
        if (begin == end)
            return; // owns nothing: steps nothing, needs no halo
        // The grid covers the owned particles and `reach` around them (a
        // particle outside it is farther than that from every owned one),
        // not the whole fluid: with 2 ranks about half the cells.
        Vec<D> lo(std::numeric_limits<Real>::max()), hi(-std::numeric_limits<Real>::max());
        for (std::size_t i = begin; i < end; ++i) {
            const Vec<D>& x = state.position[i];
            bool finite = true;
            for (int a = 0; a < D; ++a)
                finite = finite && std::isfinite(x[a]);
            if (!finite)
                continue;
            lo = glm::min(lo, x);
            hi = glm::max(hi, x);
        }
        const Real cell_size = reach / halo_subdivision;
        lo -= Vec<D>(reach + cell_size);
        hi += Vec<D>(reach + cell_size);
        std::size_t cells = 1;
        std::array<std::size_t, D> dims{};
        everyone = everyone || !(reach > 0) || !std::isfinite(reach) || !(lo[0] <= hi[0]);
        for (int a = 0; a < D && !everyone; ++a) {
            const Real extent = (hi[a] - lo[a]) / cell_size;
            everyone = !(extent < Real(max_cells_per_particle * (n + 64)));
            if (!everyone) {
                dims[a] = std::size_t(extent) + 1;
                cells *= dims[a];
                everyone = cells > max_cells_per_particle * (n + 64);
            }
        }
        if (everyone) {
            for (std::size_t i = 0; i < n; ++i)
                local_index_.push_back(static_cast<std::uint32_t>(i));
            return;
        }
        // The cell holding x, false outside the grid.
        const Real per_cell = 1 / cell_size; // h (1 + 1e-5) in `reach` covers its rounding
        auto cell_of = [&](const Vec<D>& x, std::size_t& cell) {
            cell = 0;
            for (int a = D - 1; a >= 0; --a) {
                const Real u = (x[a] - lo[a]) * per_cell;
                if (!(u >= 0 && u < Real(dims[a])))
                    return false;
                cell = cell * dims[a] + std::size_t(u);
            }
            return true;
        };
        // Cells of an owned particle, then grown by halo_subdivision cells
        // along each axis in turn: a particle within `reach` of an owned one
        // is in a marked cell.
        near_.assign(cells, 0);
        for (std::size_t i = begin; i < end; ++i)
            if (std::size_t c; cell_of(state.position[i], c))
                near_[c] = 1;
        grow_cells(dims, halo_subdivision);
        for (std::size_t i = 0; i < n; ++i) {
            std::size_t c = 0;
            if ((i >= begin && i < end) || (cell_of(state.position[i], c) && near_[c]))
                local_index_.push_back(static_cast<std::uint32_t>(i));
        }
    }

    // near_ grown by `layers` cells along each axis in turn: a cell is
    // marked when a marked cell lies within `layers` of it along the axis,
    // found by a sweep each way that keeps, for each line of cells, where
    // the last marked one was (two passes an axis, no division: the grid
    // holds 10^5-10^6 cells, and this runs every step).
    void grow_cells(const std::array<std::size_t, D>& dims, int layers) {
        const std::size_t cells = near_.size();
        std::size_t step = 1; // cells between neighbours along axis a
        for (int a = 0; a < D; ++a) {
            const std::size_t length = dims[std::size_t(a)];
            const std::ptrdiff_t reach = layers;
            grown_.assign(cells, 0);
            last_marked_.resize(step);
            for (std::size_t base = 0; base < cells; base += step * length) {
                std::fill(last_marked_.begin(), last_marked_.end(), -reach - 1);
                for (std::size_t j = 0; j < length; ++j) {
                    const std::size_t row = base + j * step;
                    for (std::size_t k = 0; k < step; ++k) {
                        if (near_[row + k])
                            last_marked_[k] = std::ptrdiff_t(j);
                        grown_[row + k] = std::ptrdiff_t(j) - last_marked_[k] <= reach;
                    }
                }
                std::fill(last_marked_.begin(), last_marked_.end(),
                          std::ptrdiff_t(length) + reach + 1);
                for (std::size_t j = length; j-- > 0;) {
                    const std::size_t row = base + j * step;
                    for (std::size_t k = 0; k < step; ++k) {
                        if (near_[row + k])
                            last_marked_[k] = std::ptrdiff_t(j);
                        grown_[row + k] |= last_marked_[k] - std::ptrdiff_t(j) <= reach;
                    }
                }
            }
            near_.swap(grown_);
            step *= length;
        }
    }

    // Which owner sends each halo particle's densities (need_, need_first_:
    // the halo's runs in local_index_, one per owner, the ranges being
    // contiguous), and which owned particles this rank sends to each rank
    // (give_index_, as positions in local_): each rank tells each owner the
    // particles it needs, by global index.
    void plan_halo() {
        const auto p = std::size_t(ranks_);
        const std::size_t begin = first_[std::size_t(rank_)];
        owned_in_local_ = 0;
        owned_offset_ = 0;
        std::fill(need_.begin(), need_.end(), 0);
        std::size_t owner = 0;
        for (std::size_t k = 0; k < local_index_.size(); ++k) {
            const std::size_t i = local_index_[k];
            while (i >= first_[owner + 1])
                ++owner;
            if (owner == std::size_t(rank_)) {
                if (owned_in_local_++ == 0)
                    owned_offset_ = k;
                continue;
            }
            if (need_[owner]++ == 0)
                need_first_[owner] = k;
        }
        MPI_Alltoall(need_.data(), 1, MPI_INT, give_.data(), 1, MPI_INT, MPI_COMM_WORLD);
        for (std::size_t r = 0; r < p; ++r)
            give_first_[r + 1] = give_first_[r] + std::size_t(give_[r]);
        give_index_.resize(give_first_[p]);
        requests_.clear();
        for (std::size_t r = 0; r < p; ++r) {
            if (give_[r] == 0)
                continue;
            requests_.emplace_back();
            MPI_Irecv(give_index_.data() + give_first_[r], give_[r], MPI_UINT32_T, int(r),
                      request_tag, MPI_COMM_WORLD, &requests_.back());
        }
        for (std::size_t s = 0; s < p; ++s) {
            if (need_[s] == 0)
                continue;
            requests_.emplace_back();
            MPI_Isend(local_index_.data() + need_first_[s], need_[s], MPI_UINT32_T, int(s),
                      request_tag, MPI_COMM_WORLD, &requests_.back());
        }
        MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
        // Global index to position in local_: the owned particles are one run.
        for (auto& i : give_index_)
            i = static_cast<std::uint32_t>(owned_offset_ + (i - begin));
        std::size_t needed = 0;
        for (const int count : need_)
            needed += std::size_t(count);
        step_halo_bytes_ = double(needed * sizeof(std::uint32_t));
    }

    void copy_local(const State<D>& state) {
        const std::size_t m = local_index_.size();
        local_.resize(m);
        const std::uint32_t* index = local_index_.data();
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < m; ++k) {
            const std::uint32_t i = index[k];
            local_.position[k] = state.position[i];
            local_.velocity[k] = state.velocity[i];
            local_.acceleration[k] = state.acceleration[i];
            local_.density[k] = state.density[i];
            local_.pressure[k] = state.pressure[i];
            local_.id[k] = state.id[i];
        }
    }

    // The owned particles' new state, and the solver's kept arrays, from
    // every rank, into `state` and kept_whole_.
    void share_results(State<D>& state, double seconds, std::span<std::vector<Real>* const> kept) {
        const std::size_t n = state.size();
        const std::size_t begin = first_[std::size_t(rank_)], end = first_[std::size_t(rank_) + 1];
        const std::size_t owned = end - begin;
        stride_ = state_stride + kept.size();
        const std::size_t stride = stride_;
        // The kept arrays the step filled (sized to what it held).
        std::uint32_t filled = 0;
        for (std::size_t a = 0; a < kept.size(); ++a)
            if (kept[a]->size() == local_.size())
                filled |= std::uint32_t(1) << a;
        if ((n * stride + std::size_t(ranks_) * trailer) >
            std::size_t(std::numeric_limits<int>::max()))
            throw std::length_error("MPI ranks: more particles than one gather can count");
        // Where the owned run starts among this rank's particles.
        const std::size_t offset = std::size_t(
            std::lower_bound(local_index_.begin(), local_index_.end(), std::uint32_t(begin)) -
            local_index_.begin());
        send_.resize(owned * stride + trailer);
#pragma omp parallel for schedule(static)
        for (std::size_t k = 0; k < owned; ++k) {
            Real* out = send_.data() + k * stride;
            const std::size_t j = offset + k;
            for (int a = 0; a < D; ++a) {
                out[a] = local_.position[j][a];
                out[D + a] = local_.velocity[j][a];
                out[2 * D + a] = local_.acceleration[j][a];
            }
            out[3 * D] = local_.density[j];
            out[3 * D + 1] = local_.pressure[j];
            for (std::size_t a = 0; a < kept.size(); ++a)
                out[state_stride + a] = filled >> a & 1 ? (*kept[a])[j] : 0;
        }
        send_[owned * stride] = double(local_.size());
        send_[owned * stride + 1] = seconds;
        send_[owned * stride + 2] = step_halo_bytes_;
        send_[owned * stride + 3] = double(filled);
        for (int r = 0; r < ranks_; ++r) {
            const std::size_t count =
                (first_[std::size_t(r) + 1] - first_[std::size_t(r)]) * stride + trailer;
            counts_[std::size_t(r)] = int(count);
            displacements_[std::size_t(r)] =
                int(first_[std::size_t(r)] * stride + std::size_t(r) * trailer);
        }
        receive_.resize(n * stride + std::size_t(ranks_) * trailer);
        MPI_Request request;
        MPI_Iallgatherv(send_.data(), int(send_.size()), MPI_DOUBLE, receive_.data(),
                        counts_.data(), displacements_.data(), MPI_DOUBLE, MPI_COMM_WORLD,
                        &request);
        MPI_Wait(&request, MPI_STATUS_IGNORE);
        // A kept array is whole when every rank filled it.
        std::uint32_t whole = ~std::uint32_t(0);
        for (int r = 0; r < ranks_; ++r) {
            const std::size_t count = first_[std::size_t(r) + 1] - first_[std::size_t(r)];
            whole &= std::uint32_t(
                receive_[std::size_t(displacements_[std::size_t(r)]) + count * stride + 3]);
        }
        for (std::size_t a = 0; a < kept.size(); ++a) {
            if (whole >> a & 1)
                kept_whole_[a].resize(n);
            else
                kept_whole_[a].clear();
        }
        for (int r = 0; r < ranks_; ++r) {
            const std::size_t from = first_[std::size_t(r)], to = first_[std::size_t(r) + 1];
            const Real* block = receive_.data() + displacements_[std::size_t(r)];
#pragma omp parallel for schedule(static)
            for (std::size_t i = from; i < to; ++i) {
                const Real* in = block + (i - from) * stride;
                for (int a = 0; a < D; ++a) {
                    state.position[i][a] = in[a];
                    state.velocity[i][a] = in[D + a];
                    state.acceleration[i][a] = in[2 * D + a];
                }
                state.density[i] = in[3 * D];
                state.pressure[i] = in[3 * D + 1];
                for (std::size_t a = 0; a < kept.size(); ++a)
                    if (whole >> a & 1)
                        kept_whole_[a][i] = in[state_stride + a];
            }
            const Real* tail = block + (to - from) * stride;
            last_owned_[std::size_t(r)] = to - from;
            last_local_[std::size_t(r)] = std::uint64_t(tail[0]);
            seconds_[std::size_t(r)] = tail[1];
            halo_bytes_ += tail[2];
        }
        record_balance(n, owned);
        if (rank_ == 0)
            record_owners(state);
    }

    // Which rank owns each particle now: the particles that changed rank
    // since the last step (where the cut or a reorder moved them) and the
    // ranks each has been owned by. Rank 0 reports them.
    void record_owners(const State<D>& state) {
        bool empty = false;
        for (int r = 0; r < ranks_; ++r) {
            empty = empty || first_[std::size_t(r) + 1] == first_[std::size_t(r)];
            for (std::size_t i = first_[std::size_t(r)]; i < first_[std::size_t(r) + 1]; ++i) {
                const std::uint32_t id = state.id[i];
                if (id >= owner_.size()) {
                    owner_.resize(std::size_t(id) + 1, -1);
                    visited_.resize(std::size_t(id) + 1, 0);
                }
                if (owner_[id] >= 0 && owner_[id] != r)
                    ++migrations_;
                owner_[id] = static_cast<std::int16_t>(r);
                if (r < 64) {
                    visited_[id] |= std::uint64_t(1) << r;
                    most_visited_ = std::max(most_visited_, std::popcount(visited_[id]));
                }
            }
        }
        steps_with_empty_rank_ += empty;
    }

    void record_balance(std::size_t n, std::size_t owned) {
        ++steps_;
        std::uint64_t local_total = 0, local_max = 0;
        double seconds_total = 0, seconds_max = 0;
        for (int r = 0; r < ranks_; ++r) {
            local_total += last_local_[std::size_t(r)];
            local_max = std::max(local_max, last_local_[std::size_t(r)]);
            seconds_total += seconds_[std::size_t(r)];
            seconds_max = std::max(seconds_max, seconds_[std::size_t(r)]);
        }
        const double work = local_total > 0 ? double(local_max) * ranks_ / double(local_total) : 1;
        const double time = seconds_total > 0 ? seconds_max * ranks_ / seconds_total : 1;
        work_imbalance_sum_ += work;
        work_imbalance_max_ = std::max(work_imbalance_max_, work);
        time_imbalance_sum_ += time;
        time_imbalance_max_ = std::max(time_imbalance_max_, time);
        halo_sum_ += local_.size() - owned;
        received_bytes_ += (n - owned) * stride_ * sizeof(Real);
    }

    const int hops_;
    const bool whole_cells_;
    const int rank_, ranks_;
    std::vector<std::size_t> first_;
    std::size_t stride_ = state_stride; // values a particle in the gather
    std::vector<std::uint32_t> local_index_;
    std::vector<std::uint8_t> near_, grown_;
    std::vector<std::ptrdiff_t> last_marked_; // grow_cells: per line across a slab
    State<D> local_;
    std::vector<Real> send_, receive_;
    std::vector<int> counts_, displacements_;
    // The halo exchange (plan_halo, share_densities).
    std::vector<int> need_, give_;
    std::vector<std::size_t> need_first_, give_first_;
    std::vector<std::uint32_t> give_index_;
    std::vector<Real> give_values_, need_values_;
    std::vector<MPI_Request> requests_;
    std::size_t owned_offset_ = 0, owned_in_local_ = 0;
    double step_halo_bytes_ = 0, halo_bytes_ = 0;
    // The solver's kept arrays for the whole state (Solver::kept_arrays).
    std::vector<std::vector<Real>> kept_whole_;
    std::vector<Real> permute_scratch_;
    // dfsph's exchanges and sums in each iteration.
    std::chrono::steady_clock::time_point sum_start_;
    double solve_exchange_seconds_ = 0;
    std::uint64_t sums_ = 0;
    bool stepped_ = false;
    std::size_t stepped_size_ = 0;
    // Balance and traffic, for run.json.
    std::vector<std::uint64_t> last_local_, last_owned_;
    std::vector<double> seconds_ = std::vector<double>(std::size_t(ranks_), 0.0);
    std::uint64_t steps_ = 0, halo_sum_ = 0, received_bytes_ = 0;
    double work_imbalance_sum_ = 0, work_imbalance_max_ = 0;
    double time_imbalance_sum_ = 0, time_imbalance_max_ = 0;
    std::vector<std::int16_t> owner_; // by particle id; -1: not seen yet
    std::vector<std::uint64_t> visited_;
    std::uint64_t migrations_ = 0, steps_with_empty_rank_ = 0;
    int most_visited_ = 0;
};

} // namespace

template <int D>
std::unique_ptr<Partition<D>> make_rank_partition(const Params<D>& params,
                                                  const EffectList<D>& effects,
                                                  const std::string& scene_file) {
    if (size() <= 1)
        return nullptr;
    // The float passes gather a cell's neighbourhood in the order of the
    // grid over the fluid and wall particles: the same grid on every rank
    // only when the domain's wall particles bound it, as they bound the
    // fluid.
    const bool single = params.precision == Precision::single;
    if (single && params.walls != WallModel::particles)
        throw InputError(scene_file, "solver.walls",
                         "single precision over MPI ranks needs wall particles (solver.walls "
                         "particles): with reflecting walls each rank's grid would differ; use "
                         "solver.precision double, or run on one rank");
    // The chain of neighbour sums after the halo exchange of densities: the
    // forces, which read the neighbours' densities (their owners'), ...
    int hops = 1;
    for (const auto& effect : effects)
        if (dynamic_cast<const SurfaceTension<D>*>(effect.get()))
            hops = 2; // ... or normals from densities, then forces from normals
    // ... then, with wcsph's carried density (solver.density_diffusion), its
    // rate, which reads the neighbours' velocities after the kick (from
    // their forces) and their renormalised density gradients (from their
    // own neighbours). dfsph's sums exchange what they read instead.
    if (params.density_diffusion > 0)
        ++hops;
    // The walls' extrapolated pressure (wcsph's solver.wall_pressure
    // extrapolated) is a sum over the fluid around each wall particle, which
    // a wall particle beside an owned one has up to a support radius further.
    if (params.wall_pressure == WallPressure::extrapolated)
        ++hops;
    return std::make_unique<RankPartition<D>>(hops, single);
}

template std::unique_ptr<Partition<2>>
make_rank_partition<2>(const Params<2>&, const EffectList<2>&, const std::string&);
template std::unique_ptr<Partition<3>>
make_rank_partition<3>(const Params<3>&, const EffectList<3>&, const std::string&);

} // namespace sph::parallel
