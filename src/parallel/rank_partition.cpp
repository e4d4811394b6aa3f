#include "parallel/rank_partition.hpp"

#include "parallel/world.hpp"
#include "scene/input_error.hpp"
#include "sph/effects/surface_tension.hpp"
#include "sph/neighbours/sorted_grid.hpp"
#include "sph/solvers/explicit_solver.hpp"
#include "sph/surface.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <mpi.h>
#include <numeric>
#include <omp.h>
#include <stdexcept>
#include <vector>

namespace sph::parallel {

namespace {

// Coarse cells at most per particle for the halo's grid; a box sparser
// than that (a far stray particle) keeps every candidate in the halo, which
// is exact, only slower.
constexpr std::size_t max_cells_per_particle = 64;
// Point-to-point tags: the candidates for another rank's halo, a rank's
// halo request (which of them it keeps), each exchange of their values in
// the step, a sum in particle order passed on to the next rank, particles
// moving to their new owner, and the spatial sort's questions and answers.
constexpr int candidate_tag = 23;
constexpr int request_tag = 24;
constexpr int values_tag = 25;
constexpr int sum_tag = 26;
constexpr int migrate_tag = 27;
constexpr int query_tag = 28;
constexpr int answer_tag = 29;
// Halo cells per reach along an axis: the halo is the owned particles' cells
// grown by this many cells, so it holds particles up to 1.5 reach away
// rather than 2 reaches with cells as large as the reach. (Thirds held 4%
// fewer at 86k particles, for 2.5 times the time to mark the cells.)
constexpr int halo_subdivision = 2;

// What each rank tells rank 0 after a step, for run.json.
enum Figure : std::size_t {
    owned_figure,
    local_figure,      // owned + halo
    seconds_figure,    // in the solver
    halo_bytes_figure, // received for the halo: candidates, requests, values
    migrated_figure,   // particles it sent to another owner since the last step
    migration_bytes_figure,
    most_visited_figure, // most ranks one of its particles has been owned by
    walls_figure,        // static boundary particles it holds
    figure_count
};

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <class T>
MPI_Datatype mpi_type() {
    if constexpr (std::is_same_v<T, double>)
        return MPI_DOUBLE;
    else
        return MPI_UINT64_T;
}

int message_size(std::size_t count) {
    if (count > std::size_t(std::numeric_limits<int>::max()))
        throw std::length_error("MPI ranks: a message larger than MPI can count");
    return int(count);
}

// One particle in a message: its place in the memory order, x, v, a, rho,
// p, id, the ranks it has been owned by (two 32-bit halves, so every entry
// is a double exactly), then the solver's kept arrays.
template <int D>
struct Record {
    static constexpr std::size_t fixed = 1 + 3 * D + 5;
    static std::size_t stride(std::size_t kept) { return fixed + kept; }
};

template <int D>
class RankPartition final : public Partition<D>, public HaloExchange<D> {
  public:
    RankPartition(int hops, bool whole_cells, Real rebalance_above)
        : hops_(hops), whole_cells_(whole_cells), rebalance_above_(rebalance_above),
          rank_(parallel::rank()), ranks_(size()) {
        const auto p = std::size_t(ranks_);
        count_.assign(p, 0);
        first_.assign(p + 1, 0);
        need_.assign(p, 0);
        need_first_.assign(p, 0);
        give_.assign(p, 0);
        give_first_.assign(p + 1, 0);
        last_local_.assign(p, 0);
        last_owned_.assign(p, 0);
        last_walls_.assign(p, 0);
        seconds_.assign(p, 0);
    }

    // ---- Collective ----------------------------------------------------
    bool any(bool mine) override {
        int in = mine ? 1 : 0, out = 0;
        MPI_Allreduce(&in, &out, 1, MPI_INT, MPI_LOR, MPI_COMM_WORLD);
        return out != 0;
    }
    void max(std::span<Real> values) override {
        MPI_Allreduce(MPI_IN_PLACE, values.data(), message_size(values.size()), MPI_DOUBLE, MPI_MAX,
                      MPI_COMM_WORLD);
    }
    Real max_over_ranks(Real value) override {
        max(std::span<Real>(&value, 1));
        return value;
    }
    int lowest(int key) override {
        struct {
            int key, rank;
        } in{key, rank_}, out{};
        MPI_Allreduce(&in, &out, 1, MPI_2INT, MPI_MINLOC, MPI_COMM_WORLD);
        return out.rank;
    }
    void broadcast(std::span<std::byte> bytes, int from) override {
        MPI_Bcast(bytes.data(), message_size(bytes.size()), MPI_BYTE, from, MPI_COMM_WORLD);
    }
    int rank() const override { return rank_; }
    std::size_t total_particles() const override { return first_[std::size_t(ranks_)]; }
    bool holds_end() const override { return rank_ + 1 == ranks_; }
    void appended(std::size_t count) override {
        count_[std::size_t(ranks_) - 1] += count;
        first_[std::size_t(ranks_)] += count;
        if (holds_end())
            visited_.resize(visited_.size() + count, own_bit());
        // New particles have no kept values yet: as in one process, the
        // solver's kept arrays no longer cover every particle.
        kept_mask_ = 0;
    }

    // ---- Partition ------------------------------------------------------
    typename Partition<D>::Share starting_share(std::size_t total) override {
        cut_evenly(total);
        return {first_[std::size_t(rank_)], count_[std::size_t(rank_)]};
    }

    void adopt(State<D>& share) override {
        if (share.size() != count_[std::size_t(rank_)])
            throw std::logic_error("a rank's starting share is not the one starting_share cut");
        visited_.assign(share.size(), own_bit());
        kept_owned_.clear();
        kept_mask_ = 0;
    }

    StepReport step(Solver<D>& solver, const Params<D>& params, Real dt, State<D>& state,
                    StepContext<D>& context) override {
        const std::size_t n = total_particles();
        // The accelerations a Verlet step reuses are as current as on one
        // process. When they are not (the first step, new particles), the
        // step computes them before it drifts by them, and nothing would
        // bound that drift beforehand: they are computed here first, where
        // the particles are, over a halo without drift (as a symplectic
        // Euler step's), the same bits as that first pass of one process.
        bool current = stepped_ && n == stepped_size_;
        const std::span<std::vector<Real>* const> kept = solver.kept_arrays();
        if (kept_owned_.size() != kept.size()) {
            kept_owned_.assign(kept.size(), {});
            kept_mask_ = 0;
        }
        auto* explicit_solver = dynamic_cast<ExplicitSolver<D>*>(&solver);
        if (params.integrator == Integrator::verlet && !current && explicit_solver) {
            choose_halo(params, 0, state, kept, context);
            context.halo = this;
            explicit_solver->refresh_accelerations(params, local_, context);
            context.halo = nullptr;
            for (std::size_t i = 0; i < state.size(); ++i)
                state.acceleration[i] = local_.acceleration[owned_offset_ + i];
            // What that pass kept (where wcsph made its cells) is kept for
            // the step, as one process keeps it.
            keep_arrays(state.size(), kept);
            current = true;
        }
        choose_halo(params, dt, state, kept, context);
        if (explicit_solver)
            explicit_solver->set_accelerations_current(current, local_.size());
        const auto start = std::chrono::steady_clock::now();
        // A rank that owns nothing (fewer particles than ranks) steps an
        // empty state: it holds no halo, so no rank exchanges with it, but
        // it takes part in the solves' sums over all particles (dfsph).
        context.halo = this;
        StepReport report = solver.step(params, dt, local_, context);
        context.halo = nullptr;
        const double seconds = seconds_since(start);
        stepped_ = true;
        stepped_size_ = n;
        keep_results(state, kept, seconds);
        // Each rank's pushes, halo included: a particle near a rank's edge is
        // pushed on every rank that holds it (docs/mpi.md).
        std::uint64_t pushes = 0;
        MPI_Allreduce(&report.obstacle_pushes, &pushes, 1, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
        report.obstacle_pushes = pushes;
        return report;
    }

    // The spatial sort over all ranks. One process sorts its particles by
    // cell key, stably (SortedGrid::cell_order): particle i goes to the
    // number of particles whose key is smaller, or equal and before i. Each
    // rank keys its own on the whole fluid's grid and sorts them; a
    // particle's new place is then its place among its rank's, plus, from
    // each other rank s, the count of s's particles before it: those with a
    // smaller key, or an equal one when s comes first. A rank whose keys lie
    // all below (above) a particle's adds all (none) of its own; for the
    // others the rank asks s, with its keys in s's span. The ranges are
    // then cut by count and each particle sent to the owner of its place.
    void reorder(State<D>& state, Real h) override {
        const std::size_t m = state.size();
        const auto p = std::size_t(ranks_);
        // The whole fluid's box of finite positions, as one process finds it.
        std::array<Real, 2 * D> box;
        box.fill(std::numeric_limits<Real>::lowest());
        for (std::size_t i = 0; i < m; ++i)
            for (int a = 0; a < D; ++a) {
                const Real v = state.position[i][a];
                if (std::abs(v) <= std::numeric_limits<Real>::max()) {
                    box[std::size_t(a)] = std::max(box[std::size_t(a)], -v);
                    box[std::size_t(D + a)] = std::max(box[std::size_t(D + a)], v);
                }
            }
        max(std::span<Real>(box));
        Vec<D> lo, hi;
        for (int a = 0; a < D; ++a) {
            lo[a] = -box[std::size_t(a)];
            hi[a] = box[std::size_t(D + a)];
        }
        const std::span<const std::uint64_t> cell_keys =
            sorter_.cell_keys(state.position, h, lo, hi);
        order_.resize(m);
        std::iota(order_.begin(), order_.end(), 0u);
        std::stable_sort(order_.begin(), order_.end(), [&](std::uint32_t x, std::uint32_t y) {
            return cell_keys[x] < cell_keys[y];
        });
        sorted_keys_.resize(m);
        for (std::size_t j = 0; j < m; ++j)
            sorted_keys_[j] = cell_keys[order_[j]];
        // Each rank's smallest and largest key and its count.
        std::array<std::uint64_t, 3> mine{m ? sorted_keys_.front() : 0, m ? sorted_keys_.back() : 0,
                                          m};
        spans_.resize(3 * p);
        MPI_Allgather(mine.data(), 3, MPI_UINT64_T, spans_.data(), 3, MPI_UINT64_T, MPI_COMM_WORLD);
        auto low = [&](std::size_t s) {
            return spans_[3 * s];
        };
        auto high = [&](std::size_t s) {
            return spans_[3 * s + 1];
        };
        auto count = [&](std::size_t s) {
            return spans_[3 * s + 2];
        };
        // Questions: this rank's distinct keys within each other rank's span.
        std::vector<std::uint64_t> questions;
        std::vector<std::size_t> question_count(p, 0);
        for (std::size_t s = 0; s < p; ++s) {
            if (s == std::size_t(rank_) || count(s) == 0)
                continue;
            auto from = std::lower_bound(sorted_keys_.begin(), sorted_keys_.end(), low(s));
            auto to = std::upper_bound(sorted_keys_.begin(), sorted_keys_.end(), high(s));
            for (auto k = from; k != to; ++k)
                if (k == from || *k != *(k - 1)) {
                    questions.push_back(*k);
                    ++question_count[s];
                }
        }
        std::vector<std::uint64_t> asked;
        std::vector<std::size_t> asked_count(p, 0);
        all_to_all(questions, question_count, asked, asked_count, query_tag);
        // Answers: for a rank before this one, how many of this rank's keys
        // are smaller than each; for one after, smaller or equal.
        std::vector<std::uint64_t> answers(asked.size());
        for (std::size_t r = 0, at = 0; r < p; ++r)
            for (std::size_t k = 0; k < asked_count[r]; ++k, ++at) {
                const auto bound =
                    r < std::size_t(rank_)
                        ? std::lower_bound(sorted_keys_.begin(), sorted_keys_.end(), asked[at])
                        : std::upper_bound(sorted_keys_.begin(), sorted_keys_.end(), asked[at]);
                answers[at] = std::uint64_t(bound - sorted_keys_.begin());
            }
        std::vector<std::uint64_t> told;
        std::vector<std::size_t> told_count(p, 0);
        all_to_all(answers, asked_count, told, told_count, answer_tag);
        // New places, in this rank's sorted order first. A rank's whole
        // count, for the particles above its span, is added from where that
        // starts by one running sum (below_[j]: counts that start at j), so
        // the ranks far away cost nothing per particle.
        places_.assign(m, 0);
        below_.assign(m + 1, 0);
        for (std::size_t j = 0; j < m; ++j)
            places_[j] = j;
        for (std::size_t s = 0, at = 0; s < p; ++s) {
            if (s == std::size_t(rank_) || count(s) == 0)
                continue;
            const std::size_t from =
                std::size_t(std::lower_bound(sorted_keys_.begin(), sorted_keys_.end(), low(s)) -
                            sorted_keys_.begin());
            const std::size_t to =
                std::size_t(std::upper_bound(sorted_keys_.begin(), sorted_keys_.end(), high(s)) -
                            sorted_keys_.begin());
            std::size_t answer = at;
            for (std::size_t j = from; j < to; ++j) {
                if (j > from && sorted_keys_[j] != sorted_keys_[j - 1])
                    ++answer;
                places_[j] += told[answer];
            }
            below_[to] += count(s);
            at += question_count[s];
        }
        std::uint64_t running = 0;
        for (std::size_t j = 0; j < m; ++j) {
            running += below_[j];
            places_[j] += running;
        }
        // places_ by sorted position -> by memory position.
        sorted_places_.resize(m);
        for (std::size_t j = 0; j < m; ++j)
            sorted_places_[order_[j]] = places_[j];
        std::vector<std::size_t> even = even_cut(total_particles());
        migrate(state, sorted_places_, even);
    }

    void rebalance(State<D>& state) override {
        const std::size_t n = total_particles();
        const std::size_t most = *std::max_element(count_.begin(), count_.end());
        if (n == 0 || Real(most) * Real(ranks_) <= rebalance_above_ * Real(n))
            return;
        const std::size_t begin = first_[std::size_t(rank_)];
        sorted_places_.resize(state.size());
        for (std::size_t i = 0; i < state.size(); ++i)
            sorted_places_[i] = begin + i;
        migrate(state, sorted_places_, even_cut(n));
        ++rebalances_;
    }

    void update_fields(Solver<D>& solver, const Params<D>& params, State<D>& state,
                       StepContext<D>& context) override {
        choose_halo(params, 0, state, {}, context);
        context.halo = this;
        solver.update_fields(params, local_, context);
        context.halo = nullptr;
        copy_owned_back(state);
    }

    void mark_buried(const NeighbourList& neighbours, Real spacing,
                     std::vector<std::uint8_t>& buried) override {
        sph::mark_buried(local_, neighbours, spacing, local_buried_);
        const auto p = std::size_t(ranks_);
        std::vector<int> counts(p), displacements(p);
        for (std::size_t r = 0; r < p; ++r) {
            counts[r] = message_size(count_[r]);
            displacements[r] = message_size(first_[r]);
        }
        if (rank_ != 0) {
            buried.assign(local_buried_.begin() + std::ptrdiff_t(owned_offset_),
                          local_buried_.begin() + std::ptrdiff_t(owned_offset_ + owned_in_local_));
            MPI_Gatherv(buried.data(), message_size(owned_in_local_), MPI_UINT8_T, nullptr, nullptr,
                        nullptr, MPI_UINT8_T, 0, MPI_COMM_WORLD);
            return;
        }
        buried.resize(total_particles());
        MPI_Gatherv(local_buried_.data() + owned_offset_, message_size(owned_in_local_),
                    MPI_UINT8_T, buried.data(), counts.data(), displacements.data(), MPI_UINT8_T, 0,
                    MPI_COMM_WORLD);
    }

    void gather(const State<D>& share, State<D>& whole) override {
        constexpr std::size_t stride = 3 * D + 3;
        const std::size_t m = share.size(), n = total_particles();
        send_.resize(m * stride);
        for (std::size_t i = 0; i < m; ++i) {
            Real* out = send_.data() + i * stride;
            for (int a = 0; a < D; ++a) {
                out[a] = share.position[i][a];
                out[D + a] = share.velocity[i][a];
                out[2 * D + a] = share.acceleration[i][a];
            }
            out[3 * D] = share.density[i];
            out[3 * D + 1] = share.pressure[i];
            out[3 * D + 2] = double(share.id[i]);
        }
        const auto p = std::size_t(ranks_);
        std::vector<int> counts(p), displacements(p);
        for (std::size_t r = 0; r < std::size_t(ranks_); ++r) {
            counts[r] = message_size(count_[r] * stride);
            displacements[r] = message_size(first_[r] * stride);
        }
        ++frames_;
        if (rank_ != 0) {
            MPI_Gatherv(send_.data(), message_size(send_.size()), MPI_DOUBLE, nullptr, nullptr,
                        nullptr, MPI_DOUBLE, 0, MPI_COMM_WORLD);
            return;
        }
        // A buffer of its own, let go after the frame: the steps' buffers
        // stay the size of a share and its halo.
        std::vector<Real> received(n * stride);
        MPI_Gatherv(send_.data(), message_size(send_.size()), MPI_DOUBLE, received.data(),
                    counts.data(), displacements.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
        whole.resize(n);
#pragma omp parallel for schedule(static)
        for (std::size_t i = 0; i < n; ++i) {
            const Real* in = received.data() + i * stride;
            for (int a = 0; a < D; ++a) {
                whole.position[i][a] = in[a];
                whole.velocity[i][a] = in[D + a];
                whole.acceleration[i][a] = in[2 * D + a];
            }
            whole.density[i] = in[3 * D];
            whole.pressure[i] = in[3 * D + 1];
            whole.id[i] = static_cast<std::uint32_t>(in[3 * D + 2]);
        }
        frame_gather_bytes_ += double((n - m) * stride * sizeof(Real));
    }

    // ---- HaloExchange (the solver, mid-step) -----------------------------
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

    // Only where the halo is one support radius deep (nothing reads a halo
    // particle's own sums: hops_ 1), the passes use neighbour lists (not
    // the float passes' whole cells), and the halo is not every particle
    // (a Verlet step whose accelerations are not current drifts the halo
    // by forces it computes itself). The rows stay in `index`, unread.
    void want_rows(NeighbourSearch<D>& search) const override {
        if (trim_rows_)
            search.want_rows(owned_offset_, owned_offset_ + owned_in_local_);
        else
            search.want_rows(0, ~std::size_t(0));
    }
    void trim_rows(NeighbourList& list) const override {
        if (!trim_rows_ || list.particle_count() != local_.size())
            return;
        const std::size_t begin = owned_offset_, end = owned_offset_ + owned_in_local_;
        const std::uint32_t first = list.start[begin], last = list.start[end];
        std::fill(list.start.begin(), list.start.begin() + std::ptrdiff_t(begin), first);
        std::fill(list.start.begin() + std::ptrdiff_t(end), list.start.end(), last);
    }

    std::size_t owned_begin() const override {
        return owned_offset_;
    }
    std::size_t owned_end() const override {
        return owned_offset_ + owned_in_local_;
    }

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

    void cover_walls_with(typename Partition<D>::WallCover cover) override {
        cover_ = std::move(cover);
    }

    nlohmann::json report() const override {
        const double steps = std::max<double>(double(steps_), 1);
        const double halo_per_step = halo_bytes_ / steps / ranks_;
        const double migration_per_step = migration_bytes_ / steps / ranks_;
        const double gather_per_step = frame_gather_bytes_ / steps;
        return {
            {"ranks", ranks_},
            {"threads_per_rank", omp_get_max_threads()},
            {"decomposition",
             "contiguous ranges of the sorted grid's cell order (Morton curve); each rank holds "
             "its own particles only, cut again by count at every spatial sort and when "
             "uneven; a step's halo comes from the ranks around (candidates by box, kept by "
             "cell), its densities from their owners mid-step; particles migrate to their new "
             "owner; each holds the wall particles around its own and its halo; the whole "
             "state is gathered on rank 0 at frame times only"},
            {"halo_support_radii", hops_},
            {"halo_bytes_received_per_step", halo_per_step},
            // dfsph: its iterations' exchanges and sums in particle order
            // (rank 0's time in them, waiting included).
            {"solve_exchange_seconds", solve_exchange_seconds_},
            {"sums_in_particle_order", sums_},
            {"steps", steps_},
            {"owned_per_rank", last_owned_},
            {"owned_and_halo_per_rank", last_local_},
            {"wall_particles_per_rank", last_walls_},
            {"imbalance",
             {{"particles_mean", work_imbalance_sum_ / steps},
              {"particles_max", work_imbalance_max_},
              {"seconds_mean", time_imbalance_sum_ / steps},
              {"seconds_max", time_imbalance_max_}}},
            {"halo_particles_per_step", double(halo_sum_) / steps / ranks_},
            // The frames' gather of the whole state (rank 0's bytes),
            // spread over the steps.
            {"gather_bytes_received_per_step", gather_per_step},
            {"frame_gathers", frames_},
            {"frame_gather_bytes_received", frame_gather_bytes_},
            {"bytes_received_per_step", halo_per_step + migration_per_step + gather_per_step},
            {"migration_bytes_per_step", migration_per_step},
            {"migrations", migrations_},
            {"rebalances", rebalances_},
            {"most_ranks_visited", most_visited_},
            {"steps_with_an_empty_rank", steps_with_empty_rank_},
            // Halos that held every particle (a step whose reach is not
            // finite): none in a sound run.
            {"whole_halos", whole_halos_},
        };
    }

  private:
    std::uint64_t own_bit() const {
        return rank_ < 64 ? std::uint64_t(1) << rank_ : 0;
    }

    static void copy_particle(const State<D>& from, std::size_t i, State<D>& to, std::size_t k) {
        to.position[k] = from.position[i];
        to.velocity[k] = from.velocity[i];
        to.acceleration[k] = from.acceleration[i];
        to.density[k] = from.density[i];
        to.pressure[k] = from.pressure[i];
        to.id[k] = from.id[i];
    }

    // Rank r owns [n r / P, n (r + 1) / P).
    std::vector<std::size_t> even_cut(std::size_t n) const {
        std::vector<std::size_t> first(std::size_t(ranks_) + 1);
        for (int r = 0; r <= ranks_; ++r)
            first[std::size_t(r)] =
                std::size_t(std::uint64_t(n) * std::uint64_t(r) / std::uint64_t(ranks_));
        return first;
    }
    void set_cut(std::vector<std::size_t> first) {
        first_ = std::move(first);
        for (std::size_t r = 0; r < std::size_t(ranks_); ++r)
            count_[r] = first_[r + 1] - first_[r];
    }
    void cut_evenly(std::size_t n) {
        set_cut(even_cut(n));
    }

    // Each rank sends `send` (grouped by destination rank, send_count[r]
    // entries for rank r, none to itself) and receives into `receive`
    // (grouped by source rank): the counts first (MPI_Alltoall), then the
    // entries point to point, non-blocking.
    template <class T>
    void all_to_all(const std::vector<T>& send, const std::vector<std::size_t>& send_count,
                    std::vector<T>& receive, std::vector<std::size_t>& receive_count, int tag) {
        const auto p = std::size_t(ranks_);
        static_assert(sizeof(std::size_t) == sizeof(std::uint64_t));
        MPI_Alltoall(send_count.data(), 1, MPI_UINT64_T, receive_count.data(), 1, MPI_UINT64_T,
                     MPI_COMM_WORLD);
        receive_count[std::size_t(rank_)] = 0;
        std::size_t total = 0;
        for (const std::size_t c : receive_count)
            total += c;
        receive.resize(total);
        requests_.clear();
        std::size_t at = 0;
        for (std::size_t s = 0; s < p; ++s) {
            if (receive_count[s] == 0)
                continue;
            requests_.emplace_back();
            MPI_Irecv(receive.data() + at, message_size(receive_count[s]), mpi_type<T>(), int(s),
                      tag, MPI_COMM_WORLD, &requests_.back());
            at += receive_count[s];
        }
        at = 0;
        for (std::size_t r = 0; r < p; ++r) {
            if (send_count[r] > 0 && r != std::size_t(rank_)) {
                requests_.emplace_back();
                MPI_Isend(send.data() + at, message_size(send_count[r]), mpi_type<T>(), int(r), tag,
                          MPI_COMM_WORLD, &requests_.back());
            }
            at += send_count[r];
        }
        MPI_Waitall(int(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE);
    }

    // Writes particle i of `state` (with its kept values and the ranks it
    // has been owned by) as a record placed at `place`.
    void pack(const State<D>& state, std::size_t i, std::uint64_t place, std::uint64_t visited,
              Real* out) const {
        out[0] = double(place);
        for (int a = 0; a < D; ++a) {
            out[1 + a] = state.position[i][a];
            out[1 + D + a] = state.velocity[i][a];
            out[1 + 2 * D + a] = state.acceleration[i][a];
        }
        out[1 + 3 * D] = state.density[i];
        out[2 + 3 * D] = state.pressure[i];
        out[3 + 3 * D] = double(state.id[i]);
        out[4 + 3 * D] = double(visited & 0xffffffffu);
        out[5 + 3 * D] = double(visited >> 32);
        for (std::size_t a = 0; a < kept_owned_.size(); ++a)
            out[Record<D>::fixed + a] = kept_mask_ >> a & 1 ? kept_owned_[a][i] : 0;
    }
    static void unpack(const Real* in, State<D>& state, std::size_t k) {
        for (int a = 0; a < D; ++a) {
            state.position[k][a] = in[1 + a];
            state.velocity[k][a] = in[1 + D + a];
            state.acceleration[k][a] = in[1 + 2 * D + a];
        }
        state.density[k] = in[1 + 3 * D];
        state.pressure[k] = in[2 + 3 * D];
        state.id[k] = static_cast<std::uint32_t>(in[3 + 3 * D]);
    }
    static std::uint64_t visited_of(const Real* in) {
        return std::uint64_t(in[4 + 3 * D]) | std::uint64_t(in[5 + 3 * D]) << 32;
    }

    // Each owned particle to the rank that owns `place[i]` under the cut
    // `first`, at place[i] - first[rank] there; the kept arrays and the
    // ranks each has been owned by travel with it.
    void migrate(State<D>& state, std::span<const std::uint64_t> place,
                 std::vector<std::size_t> first) {
        const auto p = std::size_t(ranks_);
        const std::size_t m = state.size(), kept = kept_owned_.size();
        const std::size_t stride = Record<D>::stride(kept);
        destination_.resize(m);
        std::vector<std::size_t> send_count(p, 0);
        for (std::size_t i = 0; i < m; ++i) {
            const auto r = std::size_t(std::upper_bound(first.begin(), first.end(), place[i]) -
                                       first.begin()) -
                           1;
            destination_[i] = static_cast<std::uint32_t>(r);
            send_count[r] += stride;
        }
        std::vector<std::size_t> at(p + 1, 0);
        for (std::size_t r = 0; r < p; ++r)
            at[r + 1] = at[r] + send_count[r];
        send_.resize(at[p]);
        for (std::size_t i = 0; i < m; ++i) {
            const std::size_t r = destination_[i];
            pack(state, i, place[i], visited_[i], send_.data() + at[r]);
            at[r] += stride;
        }
        std::vector<std::size_t> receive_count(p, 0);
        all_to_all(send_, send_count, receive_, receive_count, migrate_tag);
        // The new share: what stays, then what came.
        const auto me = std::size_t(rank_);
        const std::size_t begin = first[me], owned = first[me + 1] - first[me];
        State<D> next;
        next.resize(owned);
        std::vector<std::vector<Real>> next_kept(kept);
        for (std::size_t a = 0; a < kept; ++a)
            if (kept_mask_ >> a & 1)
                next_kept[a].resize(owned);
        std::vector<std::uint64_t> next_visited(owned, 0);
        auto place_record = [&](const Real* in, bool moved) {
            const std::size_t k = std::size_t(in[0]) - begin;
            unpack(in, next, k);
            for (std::size_t a = 0; a < kept; ++a)
                if (kept_mask_ >> a & 1)
                    next_kept[a][k] = in[Record<D>::fixed + a];
            next_visited[k] = visited_of(in) | own_bit();
            if (moved)
                most_visited_here_ = std::max(most_visited_here_, std::popcount(next_visited[k]));
        };
        const std::size_t stay_from = at[me] - send_count[me];
        for (std::size_t k = 0; k < send_count[me]; k += stride)
            place_record(send_.data() + stay_from + k, false);
        for (std::size_t k = 0; k < receive_.size(); k += stride)
            place_record(receive_.data() + k, true);
        std::size_t moved = 0;
        for (std::size_t r = 0; r < p; ++r)
            if (r != me)
                moved += send_count[r] / stride;
        migrated_ += moved;
        migration_bytes_here_ += double(receive_.size() * sizeof(Real));
        state = std::move(next);
        kept_owned_ = std::move(next_kept);
        visited_ = std::move(next_visited);
        set_cut(std::move(first));
    }

    // The float passes' cells are as wide as h, and their skin wider
    // (solver.cell_skin), made where the particles were up to half the skin
    // from where they are: two particles in cells within reach of each
    // other are now up to one skin further apart than the cells say.
    Real cell_width(const Params<D>& params) const {
        return params.h * (1 + (whole_cells_ ? params.cell_skin : 0)) * (1 + 1e-5);
    }
    Real skin_width(const Params<D>& params) const {
        return whole_cells_ ? params.cell_skin * params.h : 0;
    }

    // The box within which the step may look for boundary particles: a
    // support radius (and a Verlet step's drift) around every particle this
    // rank holds, owned or halo; for the float passes, which read every
    // particle of the cells around a particle's cell (as wide as h), two.
    void cover_walls(const Params<D>& params) {
        if (!cover_)
            return;
        Vec<D> lo(std::numeric_limits<Real>::max()), hi(-std::numeric_limits<Real>::max());
        for (const Vec<D>& x : local_.position)
            if (finite(x)) {
                lo = glm::min(lo, x);
                hi = glm::max(hi, x);
            }
        const Real margin =
            Real(whole_cells_ ? 2 : 1) * (cell_width(params) + 2 * move_) * (1 + 1e-6) +
            skin_width(params);
        walls_held_here_ = cover_(Box<D>{lo - margin, hi + margin});
    }

    // The halo a pass needs (gather_halo with dt, then the requests and
    // the walls around it), timed as the rank halo stage.
    void choose_halo(const Params<D>& params, Real dt, const State<D>& state,
                     std::span<std::vector<Real>* const> kept, StepContext<D>& context) {
        auto timed = context.time(Stage::rank_halo);
        gather_halo(params, dt, state, kept);
        plan_halo();
        cover_walls(params);
    }

    // The step's particles (local_): the owned ones and, from the other
    // ranks, those within the halo's reach of one, in the memory order of
    // the whole simulation (local_index_: their places in it). Each rank
    // sends every rank the owned particles inside its box grown by the
    // reach (candidates); each keeps those in cells near its own particles.
    void gather_halo(const Params<D>& params, Real dt, const State<D>& state,
                     std::span<std::vector<Real>* const> kept) {
        const auto p = std::size_t(ranks_);
        const auto me = std::size_t(rank_);
        const std::size_t m = state.size();
        // How far a Verlet step moves a particle before its forces (half-kick,
        // then drift) widens every link of the chain, at both ends. The other
        // steps (symplectic Euler; dfsph, whose redone halves are steps of
        // their own) find every neighbour where the particles are at their
        // start and move them only at their end: no allowance.
        Real& move = move_;
        move = 0;
        if (params.integrator == Integrator::verlet) {
            std::array<Real, 2> rates{0, 0};
            for (std::size_t i = 0; i < m; ++i) {
                rates[0] = std::max(rates[0], squared_length<D>(state.velocity[i]));
                rates[1] = std::max(rates[1], squared_length<D>(state.acceleration[i]));
            }
            max(std::span<Real>(rates));
            move = dt * std::sqrt(rates[0]) + dt * dt * std::sqrt(rates[1]);
        }
        // The float passes (solver.precision single) sum over every particle
        // of the 3^D cells around a particle's cell, a lane per candidate:
        // the same bits need the same candidates, every particle of the
        // cells within `hops` cells of an owned one's, so one cell further.
        const Real reach =
            Real(hops_ + (whole_cells_ ? 1 : 0)) * (cell_width(params) + 2 * move) * (1 + 1e-6) +
            skin_width(params);
        // A reach that is not finite (speeds blown up): every particle.
        const bool everyone = !(reach > 0) || !std::isfinite(reach);
        whole_halos_ += everyone ? 1 : 0;
        trim_rows_ = hops_ == 1 && !whole_cells_ && !everyone;
        // This rank's box: its owned finite positions.
        Vec<D> lo(std::numeric_limits<Real>::max()), hi(-std::numeric_limits<Real>::max());
        for (std::size_t i = 0; i < m; ++i) {
            const Vec<D>& x = state.position[i];
            if (finite(x)) {
                lo = glm::min(lo, x);
                hi = glm::max(hi, x);
            }
        }
        const Real cell_size = reach / halo_subdivision;
        const Real margin = reach + cell_size;
        std::array<Real, 2 * D> mine;
        for (int a = 0; a < D; ++a) {
            mine[std::size_t(a)] = lo[a] - margin;
            mine[std::size_t(D + a)] = hi[a] + margin;
        }
        step_halo_bytes_ = 0;
        boxes_.resize(2 * D * p);
        MPI_Allgather(mine.data(), 2 * D, MPI_DOUBLE, boxes_.data(), 2 * D, MPI_DOUBLE,
                      MPI_COMM_WORLD);
        // Which of this rank's particles another rank may need: those in a
        // coarse cell (as wide as the reach) beside one of its particles'.
        // Each rank sends its occupied coarse cells to the ranks whose boxes
        // meet its own; the candidates it gets back lie within two cells of
        // its particles, a few times the halo rather than the whole box.
        const std::size_t stride = Record<D>::stride(kept_owned_.size());
        std::vector<std::size_t> send_count(p, 0), receive_count(p, 0);
        auto meets = [&](std::size_t s) {
            const Real* theirs = boxes_.data() + 2 * D * s;
            for (int a = 0; a < D; ++a)
                if (!(mine[std::size_t(a)] <= theirs[D + a] &&
                      theirs[a] <= mine[std::size_t(D + a)]))
                    return false;
            return true;
        };
        if (!everyone) {
            index_cells(state, reach);
            std::vector<std::size_t> list_count(p, 0);
            std::vector<std::uint64_t> lists;
            for (std::size_t s = 0; s < p; ++s)
                if (s != me && m > 0 && count_[s] > 0 && meets(s)) {
                    list_count[s] = cells_.size();
                    lists.insert(lists.end(), cells_.begin(), cells_.end());
                }
            all_to_all(lists, list_count, their_cells_, receive_count, candidate_tag);
            step_halo_bytes_ = double(their_cells_.size() * sizeof(std::uint64_t));
        }
        // Candidates for each rank, in memory order: every particle when
        // every one is in the halo, else those beside the rank's cells.
        std::size_t total = 0;
        candidate_index_.clear();
        for (std::size_t s = 0, list = 0; s < p; ++s) {
            const std::size_t first_candidate = candidate_index_.size();
            if (everyone) {
                if (s != me && count_[s] > 0)
                    for (std::size_t i = 0; i < m; ++i)
                        candidate_index_.push_back(static_cast<std::uint32_t>(i));
            } else if (receive_count[s] > 0) {
                // This rank's cells beside (or at) one of rank s's (its
                // list is sorted), then the particles in them.
                const auto theirs = std::span(their_cells_).subspan(list, receive_count[s]);
                list += receive_count[s];
                mark_beside(theirs);
                for (std::size_t i = 0; i < m; ++i)
                    if (particle_cell_[i] != ~std::uint64_t(0) && beside_[particle_cell_[i]])
                        candidate_index_.push_back(static_cast<std::uint32_t>(i));
            }
            send_count[s] = (candidate_index_.size() - first_candidate) * stride;
            total += send_count[s];
        }
        send_.resize(total);
        for (std::size_t k = 0; k < candidate_index_.size(); ++k) {
            const std::size_t i = candidate_index_[k];
            pack(state, i, first_[me] + i, 0, send_.data() + k * stride);
        }
        all_to_all(send_, send_count, receive_, receive_count, candidate_tag);
        step_halo_bytes_ += double(receive_.size() * sizeof(Real));
        // Which candidates to keep: those in a cell within the reach of an
        // owned particle's (all when every particle is in the halo).
        const std::size_t candidates = receive_.size() / stride;
        keep_.assign(candidates, everyone ? 1 : 0);
        if (!everyone && m > 0 && candidates > 0)
            mark_near(lo - Vec<D>(margin), hi + Vec<D>(margin), margin, cell_size, state, stride);
        // local_: candidates from the ranks before this one, the owned
        // particles, then candidates from the ranks after it.
        std::size_t halo = 0;
        for (const std::uint8_t k : keep_)
            halo += k;
        const std::size_t n_local = halo + m;
        local_.resize(n_local);
        local_index_.resize(n_local);
        for (std::size_t a = 0; a < kept.size(); ++a) {
            if (kept_mask_ >> a & 1)
                kept[a]->resize(n_local);
            else
                kept[a]->clear();
        }
        std::fill(need_.begin(), need_.end(), 0);
        std::size_t k = 0, c = 0, record = 0;
        auto take_candidates_from = [&](std::size_t s) {
            for (std::size_t e = 0; e < receive_count[s]; e += stride, ++c) {
                const Real* in = receive_.data() + (record + e);
                if (!keep_[c])
                    continue;
                if (need_[s]++ == 0)
                    need_first_[s] = k;
                unpack(in, local_, k);
                local_index_[k] = static_cast<std::uint32_t>(in[0]);
                for (std::size_t a = 0; a < kept.size(); ++a)
                    if (kept_mask_ >> a & 1)
                        (*kept[a])[k] = in[Record<D>::fixed + a];
                ++k;
            }
            record += receive_count[s];
        };
        for (std::size_t s = 0; s < me; ++s)
            take_candidates_from(s);
        owned_offset_ = k;
        owned_in_local_ = m;
        for (std::size_t i = 0; i < m; ++i, ++k) {
            copy_particle(state, i, local_, k);
            local_index_[k] = static_cast<std::uint32_t>(first_[me] + i);
            for (std::size_t a = 0; a < kept.size(); ++a)
                if (kept_mask_ >> a & 1)
                    (*kept[a])[k] = kept_owned_[a][i];
        }
        for (std::size_t s = me + 1; s < p; ++s)
            take_candidates_from(s);
    }

    // The coarse cell holding x, cells `size` wide from the origin, each
    // coordinate within +-2^20 (farther cells merge at that edge: two
    // particles a cell apart stay at most a cell apart).
    using CoarseCell = std::array<std::int64_t, D>;
    static constexpr std::int64_t coarse_limit = std::int64_t(1) << 20;
    static CoarseCell coarse_cell(const Vec<D>& x, Real size) {
        CoarseCell c;
        // Cells a hair wider than `size`: two points `size` apart, rounded,
        // are never two cells apart.
        const Real per_cell = 1 / (size * (1 + 1e-9));
        for (int a = 0; a < D; ++a) {
            const Real u = std::floor(x[a] * per_cell);
            c[std::size_t(a)] = u < Real(-coarse_limit)      ? -coarse_limit
                                : u > Real(coarse_limit - 1) ? coarse_limit - 1
                                                             : std::int64_t(u);
        }
        return c;
    }
    static std::uint64_t coarse_key(const CoarseCell& c) {
        std::uint64_t key = 0;
        for (int a = 0; a < D; ++a)
            key = key << 21 | std::uint64_t(c[std::size_t(a)] + coarse_limit);
        return key;
    }
    // The keys of the 3^D cells around the cell of `key`, itself included.
    static void add_neighbourhood(std::uint64_t key, std::vector<std::uint64_t>& out) {
        const CoarseCell c = cell_of_key(key);
        constexpr int around = D == 2 ? 9 : 27;
        for (int k = 0; k < around; ++k) {
            CoarseCell n = c;
            int rest = k;
            bool inside = true;
            for (int a = 0; a < D; ++a) {
                n[std::size_t(a)] += rest % 3 - 1;
                rest /= 3;
                inside = inside && n[std::size_t(a)] >= -coarse_limit &&
                         n[std::size_t(a)] < coarse_limit;
            }
            if (inside)
                out.push_back(coarse_key(n));
        }
    }

    // cells_: the coarse cells (as wide as `size`) of this rank's finite
    // particles, each once; particle_cell_[i]: the index of particle i's
    // in cells_ (~0 when not finite). On a dense table over the particles'
    // cells, or, when they are too sparse for one, by sorting.
    void index_cells(const State<D>& state, Real size) {
        const std::size_t m = state.size();
        constexpr std::uint64_t none = ~std::uint64_t(0);
        cells_.clear();
        particle_cell_.assign(m, none);
        coarse_.resize(m);
        CoarseCell lo, hi;
        lo.fill(coarse_limit);
        hi.fill(-coarse_limit);
        for (std::size_t i = 0; i < m; ++i)
            if (finite(state.position[i])) {
                coarse_[i] = coarse_cell(state.position[i], size);
                for (std::size_t a = 0; a < D; ++a) {
                    lo[a] = std::min(lo[a], coarse_[i][a]);
                    hi[a] = std::max(hi[a], coarse_[i][a]);
                }
            }
        std::size_t volume = 1;
        std::array<std::size_t, D> dims{};
        const std::size_t limit = max_cells_per_particle * (m + 64);
        for (std::size_t a = 0; a < D && lo[0] <= hi[0]; ++a) {
            dims[a] = std::size_t(hi[a] - lo[a] + 1);
            volume = dims[a] > limit / volume ? limit + 1 : volume * dims[a];
        }
        if (volume <= limit) {
            cell_index_.assign(volume, std::uint32_t(-1));
            for (std::size_t i = 0; i < m; ++i) {
                if (!finite(state.position[i]))
                    continue;
                std::size_t at = 0;
                for (int a = D - 1; a >= 0; --a)
                    at = at * dims[std::size_t(a)] +
                         std::size_t(coarse_[i][std::size_t(a)] - lo[std::size_t(a)]);
                if (cell_index_[at] == std::uint32_t(-1)) {
                    cell_index_[at] = static_cast<std::uint32_t>(cells_.size());
                    cells_.push_back(coarse_key(coarse_[i]));
                }
                particle_cell_[i] = cell_index_[at];
            }
            return;
        }
        for (std::size_t i = 0; i < m; ++i)
            if (finite(state.position[i]))
                cells_.push_back(coarse_key(coarse_[i]));
        std::sort(cells_.begin(), cells_.end());
        cells_.erase(std::unique(cells_.begin(), cells_.end()), cells_.end());
        for (std::size_t i = 0; i < m; ++i)
            if (finite(state.position[i]))
                particle_cell_[i] = std::uint64_t(
                    std::lower_bound(cells_.begin(), cells_.end(), coarse_key(coarse_[i])) -
                    cells_.begin());
    }

    static CoarseCell cell_of_key(std::uint64_t key) {
        CoarseCell c;
        for (int a = D - 1; a >= 0; --a) {
            c[std::size_t(a)] = std::int64_t(key & ((std::uint64_t(1) << 21) - 1)) - coarse_limit;
            key >>= 21;
        }
        return c;
    }

    // beside_[c] = 1 for each of this rank's cells (cells_) at or beside
    // one of `theirs` (another rank's): on a mask of their cells
    // grown by one, or, when their cells are too sparse for one, by
    // looking each neighbour up in their list.
    void mark_beside(std::span<const std::uint64_t> theirs) {
        beside_.assign(cells_.size(), 0);
        CoarseCell lo, hi;
        lo.fill(coarse_limit);
        hi.fill(-coarse_limit);
        for (const std::uint64_t key : theirs) {
            const CoarseCell c = cell_of_key(key);
            for (std::size_t a = 0; a < D; ++a) {
                lo[a] = std::min(lo[a], c[a] - 1);
                hi[a] = std::max(hi[a], c[a] + 1);
            }
        }
        std::size_t volume = 1;
        std::array<std::size_t, D> dims{};
        for (std::size_t a = 0; a < D; ++a) {
            dims[a] = std::size_t(hi[a] - lo[a] + 1);
            volume = dims[a] > max_cells_per_particle * (theirs.size() + 64) / volume
                         ? std::numeric_limits<std::size_t>::max()
                         : volume * dims[a];
        }
        if (volume > max_cells_per_particle * (theirs.size() + 64)) {
            sorted_theirs_.assign(theirs.begin(), theirs.end());
            std::sort(sorted_theirs_.begin(), sorted_theirs_.end());
            for (std::size_t c = 0; c < cells_.size(); ++c) {
                around_.clear();
                add_neighbourhood(cells_[c], around_);
                for (const std::uint64_t key : around_)
                    if (std::binary_search(sorted_theirs_.begin(), sorted_theirs_.end(), key)) {
                        beside_[c] = 1;
                        break;
                    }
            }
            return;
        }
        auto index = [&](const CoarseCell& c) {
            std::size_t at = 0;
            for (int a = D - 1; a >= 0; --a)
                at =
                    at * dims[std::size_t(a)] + std::size_t(c[std::size_t(a)] - lo[std::size_t(a)]);
            return at;
        };
        mask_.assign(volume, 0);
        constexpr int around = D == 2 ? 9 : 27;
        for (const std::uint64_t key : theirs) {
            const CoarseCell c = cell_of_key(key);
            for (int k = 0; k < around; ++k) {
                CoarseCell n = c;
                for (int a = 0, rest = k; a < D; ++a, rest /= 3)
                    n[std::size_t(a)] += rest % 3 - 1;
                mask_[index(n)] = 1;
            }
        }
        for (std::size_t c = 0; c < cells_.size(); ++c) {
            const CoarseCell mine = cell_of_key(cells_[c]);
            bool inside = true;
            for (std::size_t a = 0; a < D; ++a)
                inside = inside && mine[a] >= lo[a] && mine[a] <= hi[a];
            beside_[c] = inside && mask_[index(mine)];
        }
    }

    static bool finite(const Vec<D>& x) {
        for (int a = 0; a < D; ++a)
            if (!std::isfinite(x[a]))
                return false;
        return true;
    }

    // keep_[c] = 1 for each received candidate in a cell of the grid over
    // [lo, hi] that lies within halo_subdivision cells of an owned
    // particle's cell: a particle within the reach of an owned one is in
    // such a cell. A grid too large for the particles keeps them all.
    void mark_near(Vec<D> lo, Vec<D> hi, Real margin, Real cell_size, const State<D>& state,
                   std::size_t stride) {
        const std::size_t n = state.size() + keep_.size();
        // Only where the candidates are: their box grown by the margin,
        // within the owned particles' (the candidates lie along the rank's
        // border, the owned box around all of it).
        Vec<D> candidates_lo(std::numeric_limits<Real>::max());
        Vec<D> candidates_hi(-std::numeric_limits<Real>::max());
        for (std::size_t c = 0; c < keep_.size(); ++c) {
            const Real* in = receive_.data() + c * stride;
            for (int a = 0; a < D; ++a)
                if (std::isfinite(in[1 + a])) {
                    candidates_lo[a] = std::min(candidates_lo[a], in[1 + a]);
                    candidates_hi[a] = std::max(candidates_hi[a], in[1 + a]);
                }
        }
        for (int a = 0; a < D; ++a) {
            lo[a] = std::max(lo[a], candidates_lo[a] - margin);
            hi[a] = std::min(hi[a], candidates_hi[a] + margin);
            if (!(lo[a] <= hi[a]))
                return; // no candidate near an owned particle (or none finite)
        }
        std::size_t cells = 1;
        std::array<std::size_t, D> dims{};
        for (int a = 0; a < D; ++a) {
            const Real extent = (hi[a] - lo[a]) / cell_size;
            if (!(extent < Real(max_cells_per_particle * (n + 64)))) {
                std::fill(keep_.begin(), keep_.end(), 1);
                return;
            }
            dims[std::size_t(a)] = std::size_t(extent) + 1;
            cells *= dims[std::size_t(a)];
            if (cells > max_cells_per_particle * (n + 64)) {
                std::fill(keep_.begin(), keep_.end(), 1);
                return;
            }
        }
        const Real per_cell = 1 / cell_size; // h (1 + 1e-5) in the reach covers its rounding
        auto cell_of = [&](const Vec<D>& x, std::size_t& cell) {
            cell = 0;
            for (int a = D - 1; a >= 0; --a) {
                const Real u = (x[a] - lo[a]) * per_cell;
                if (!(u >= 0 && u < Real(dims[std::size_t(a)])))
                    return false;
                cell = cell * dims[std::size_t(a)] + std::size_t(u);
            }
            return true;
        };
        near_.assign(cells, 0);
        for (std::size_t i = 0; i < state.size(); ++i)
            if (std::size_t c; cell_of(state.position[i], c))
                near_[c] = 1;
        grow_cells(dims, halo_subdivision);
        for (std::size_t c = 0; c < keep_.size(); ++c) {
            const Real* in = receive_.data() + c * stride;
            Vec<D> x;
            for (int a = 0; a < D; ++a)
                x[a] = in[1 + a];
            std::size_t cell = 0;
            keep_[c] = cell_of(x, cell) && near_[cell];
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
    // the halo's runs in local_, one per owner), and which owned particles
    // this rank sends to each rank (give_index_, as positions in local_):
    // each rank tells each owner which of its candidates it kept, by place.
    void plan_halo() {
        const auto p = std::size_t(ranks_);
        const std::size_t begin = first_[std::size_t(rank_)];
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
        // Place in the memory order to position in local_.
        for (auto& i : give_index_)
            i = static_cast<std::uint32_t>(owned_offset_ + (i - begin));
        std::size_t needed = 0;
        for (const int count : need_)
            needed += std::size_t(count);
        step_halo_bytes_ += double(needed * sizeof(std::uint32_t));
    }

    // Values of the owned particles that other ranks' halos hold, `width`
    // a particle: pack(k, out) writes local particle k's, unpack(j, in)
    // stores halo particle j's from its owner.
    template <class Pack, class Unpack>
    void exchange(std::size_t width, Pack pack_value, Unpack unpack_value) {
        const auto p = std::size_t(ranks_);
        give_values_.resize(width * give_index_.size());
        for (std::size_t k = 0; k < give_index_.size(); ++k)
            pack_value(give_index_[k], give_values_.data() + width * k);
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
                unpack_value(need_first_[s] + std::size_t(k), need_values_.data() + at);
        step_halo_bytes_ += double(at * sizeof(Real));
    }

    // The owned particles' new state back into `state`, and the solver's
    // kept arrays into kept_owned_ (kept only where every rank's step
    // filled them, as one process keeps them only when they cover every
    // particle); the step's figures to rank 0.
    void copy_owned_back(State<D>& state) const {
        for (std::size_t i = 0; i < state.size(); ++i) {
            const std::size_t k = owned_offset_ + i;
            state.position[i] = local_.position[k];
            state.velocity[i] = local_.velocity[k];
            state.acceleration[i] = local_.acceleration[k];
            state.density[i] = local_.density[k];
            state.pressure[i] = local_.pressure[k];
        }
    }

    // The owned particles' entries of the solver's kept arrays (m owned),
    // where every rank's pass filled them.
    void keep_arrays(std::size_t m, std::span<std::vector<Real>* const> kept) {
        std::uint32_t filled = 0;
        for (std::size_t a = 0; a < kept.size(); ++a)
            if (kept[a]->size() == local_.size())
                filled |= std::uint32_t(1) << a;
        MPI_Allreduce(MPI_IN_PLACE, &filled, 1, MPI_UINT32_T, MPI_BAND, MPI_COMM_WORLD);
        kept_mask_ = filled;
        for (std::size_t a = 0; a < kept.size(); ++a) {
            if (kept_mask_ >> a & 1)
                kept_owned_[a].assign(kept[a]->begin() + std::ptrdiff_t(owned_offset_),
                                      kept[a]->begin() + std::ptrdiff_t(owned_offset_ + m));
            else
                kept_owned_[a].clear();
        }
    }

    void keep_results(State<D>& state, std::span<std::vector<Real>* const> kept, double seconds) {
        const std::size_t m = state.size();
        copy_owned_back(state);
        keep_arrays(m, kept);
        std::array<double, figure_count> figures{};
        figures[owned_figure] = double(m);
        figures[local_figure] = double(local_.size());
        figures[seconds_figure] = seconds;
        figures[halo_bytes_figure] = step_halo_bytes_;
        figures[migrated_figure] = double(migrated_);
        figures[migration_bytes_figure] = migration_bytes_here_;
        figures[most_visited_figure] = double(most_visited_here_);
        figures[walls_figure] = double(walls_held_here_);
        migrated_ = 0;
        migration_bytes_here_ = 0;
        gathered_figures_.resize(figure_count * std::size_t(ranks_));
        MPI_Gather(figures.data(), int(figure_count), MPI_DOUBLE, gathered_figures_.data(),
                   int(figure_count), MPI_DOUBLE, 0, MPI_COMM_WORLD);
        if (rank_ == 0)
            record_step();
    }

    // Rank 0: balance and traffic from every rank's figures.
    void record_step() {
        ++steps_;
        const auto p = std::size_t(ranks_);
        double local_total = 0, local_max = 0, seconds_total = 0, seconds_max = 0;
        bool empty = false;
        for (std::size_t r = 0; r < p; ++r) {
            const double* f = gathered_figures_.data() + figure_count * r;
            last_owned_[r] = std::uint64_t(f[owned_figure]);
            last_local_[r] = std::uint64_t(f[local_figure]);
            last_walls_[r] = std::uint64_t(f[walls_figure]);
            seconds_[r] = f[seconds_figure];
            local_total += f[local_figure];
            local_max = std::max(local_max, f[local_figure]);
            seconds_total += f[seconds_figure];
            seconds_max = std::max(seconds_max, f[seconds_figure]);
            halo_bytes_ += f[halo_bytes_figure];
            migrations_ += std::uint64_t(f[migrated_figure]);
            migration_bytes_ += f[migration_bytes_figure];
            most_visited_ = std::max(most_visited_, int(f[most_visited_figure]));
            halo_sum_ += std::uint64_t(f[local_figure] - f[owned_figure]);
            empty = empty || f[owned_figure] == 0;
        }
        const double work = local_total > 0 ? local_max * ranks_ / local_total : 1;
        const double time = seconds_total > 0 ? seconds_max * ranks_ / seconds_total : 1;
        work_imbalance_sum_ += work;
        work_imbalance_max_ = std::max(work_imbalance_max_, work);
        time_imbalance_sum_ += time;
        time_imbalance_max_ = std::max(time_imbalance_max_, time);
        steps_with_empty_rank_ += empty;
    }

    const int hops_;
    const bool whole_cells_;
    const Real rebalance_above_;
    const int rank_, ranks_;
    // The cut: rank r owns places [first_[r], first_[r + 1]) of the memory
    // order, count_[r] particles.
    std::vector<std::size_t> count_, first_;
    // Per owned particle: the solver's kept arrays (array a kept when bit a
    // of kept_mask_ is set, the same on every rank) and the ranks it has
    // been owned by (a bit each, the first 64 ranks).
    std::vector<std::vector<Real>> kept_owned_;
    std::uint32_t kept_mask_ = 0;
    std::vector<std::uint64_t> visited_;
    // The step's particles and their places in the memory order.
    State<D> local_;
    std::vector<std::uint32_t> local_index_;
    std::vector<std::uint8_t> local_buried_;
    // The halo's choice: every rank's box, this rank's coarse cells and
    // those beside another rank's, the candidates it sends.
    std::vector<Real> boxes_;
    std::vector<std::uint64_t> cells_, their_cells_, particle_cell_, around_;
    std::vector<std::uint8_t> beside_, mask_;
    std::vector<CoarseCell> coarse_;
    std::vector<std::uint32_t> cell_index_;
    std::vector<std::uint64_t> sorted_theirs_;
    std::vector<std::uint32_t> candidate_index_;
    std::vector<std::uint8_t> keep_;
    std::vector<std::uint8_t> near_, grown_;
    std::vector<std::ptrdiff_t> last_marked_; // grow_cells: per line across a slab
    std::vector<Real> send_, receive_;
    // The halo exchange (plan_halo, share_densities).
    std::vector<int> need_, give_;
    std::vector<std::size_t> need_first_, give_first_;
    std::vector<std::uint32_t> give_index_;
    std::vector<Real> give_values_, need_values_;
    std::vector<MPI_Request> requests_;
    std::size_t owned_offset_ = 0, owned_in_local_ = 0;
    bool trim_rows_ = false; // trim_rows() empties the halo's rows this step
    double step_halo_bytes_ = 0;
    // The spatial sort and migration.
    SortedGrid<D> sorter_;
    std::vector<std::uint32_t> order_, destination_;
    std::vector<std::uint64_t> sorted_keys_, spans_, places_, sorted_places_, below_;
    std::uint64_t migrated_ = 0;
    double migration_bytes_here_ = 0;
    int most_visited_here_ = 1;
    // dfsph's exchanges and sums in each iteration.
    std::chrono::steady_clock::time_point sum_start_;
    double solve_exchange_seconds_ = 0;
    std::uint64_t sums_ = 0;
    bool stepped_ = false;
    std::size_t stepped_size_ = 0;
    // The boundary particles this rank holds (Simulation's, laid by box).
    typename Partition<D>::WallCover cover_;
    Real move_ = 0; // the last halo's Verlet drift allowance
    std::size_t walls_held_here_ = 0;
    std::uint64_t whole_halos_ = 0;
    // Balance and traffic, for run.json (rank 0).
    std::vector<double> gathered_figures_;
    std::vector<std::uint64_t> last_local_, last_owned_, last_walls_;
    std::vector<double> seconds_;
    std::uint64_t steps_ = 0, halo_sum_ = 0, frames_ = 0, rebalances_ = 0;
    double halo_bytes_ = 0, migration_bytes_ = 0, frame_gather_bytes_ = 0;
    double work_imbalance_sum_ = 0, work_imbalance_max_ = 0;
    double time_imbalance_sum_ = 0, time_imbalance_max_ = 0;
    std::uint64_t migrations_ = 0, steps_with_empty_rank_ = 0;
    int most_visited_ = 1;
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
    return std::make_unique<RankPartition<D>>(hops, single, params.rebalance_above);
}

template std::unique_ptr<Partition<2>>
make_rank_partition<2>(const Params<2>&, const EffectList<2>&, const std::string&);
template std::unique_ptr<Partition<3>>
make_rank_partition<3>(const Params<3>&, const EffectList<3>&, const std::string&);

} // namespace sph::parallel
