#pragma once
// `dfsph`: divergence-free SPH (Bender & Koschier 2015, "Divergence-free
// smoothed particle hydrodynamics"; 2017, "Divergence-Free SPH for
// Incompressible and Viscous Fluids", algorithms 1-3). Two pressure solves per
// step keep the fluid incompressible with large time steps:
//   - the divergence solve makes the velocity field divergence-free
//     (D rho / Dt = 0), to solver.divergence_tolerance;
//   - the density solve corrects the predicted density rho* = rho + dt D rho / Dt
//     back to rho0, to solver.tolerance (mean compression, percent).
// Both solve for a per-particle stiffness by Jacobi-like iterations with the
// factor alpha_i = 1 / (|sum_j m grad W_ij|^2 + sum_j |m grad W_ij|^2)
// (Bender & Koschier 2017, eq. 9, with the density folded in). Walls are
// boundary particles (Akinci et al. 2012) that contribute to rho and to
// D rho / Dt (with their velocity, when a paddle moves them), and push back
// with the fluid particle's own stiffness: each wall particle mirrors the
// fluid particle in the force and in the rate alike (dfsph.cpp's notation).
// The density the solves hold at rho0 is summed each step, or carried by the
// continuity equation (solver.density), which has no deficit at a free
// surface.

#include "sph/effects/artificial_viscosity.hpp"
#include "sph/effects/laminar_viscosity.hpp"
#include "sph/solvers/solver.hpp"

#include <array>
#include <vector>

namespace sph {

// The iterations' pair loops take slice_lanes particles at a time, one to
// a lane of a register of floats (GCC's vector extension).
inline constexpr std::size_t slice_lanes = 8;
using Lanes = float __attribute__((vector_size(4 * slice_lanes)));

// Incompressible: no sound condition on the step; its own integration scheme.
// Monaghan's artificial viscosity on by default, as in wcsph and with its
// alpha h c (c from material.bulk_modulus, so one scene dissipates alike in
// both): without it water (1e-3 Pa.s, nothing resolved damps) at rest boils
// from the noise each step's solve leaves, and blew up in a 2D tank within
// 1 s; the 3D tank moved at 0.15 m/s (docs/validation.md, "Water at rest").
inline constexpr SolverCapabilities dfsph_capabilities{.name = "dfsph",
                                                       .kind = SolverKind::dfsph,
                                                       .carries_sound = false,
                                                       .supports_verlet = false,
                                                       .default_artificial_viscosity = true,
                                                       .reorder_every = 1};

template <int D>
class DfsphSolver final : public Solver<D> {
  public:
    explicit DfsphSolver(KernelKind kernel) : kernel_(kernel) {}
    // kept_ points into this object.
    DfsphSolver(const DfsphSolver&) = delete;
    DfsphSolver& operator=(const DfsphSolver&) = delete;
    std::string_view name() const override { return "dfsph"; }
    TimeStepModel time_step_model() const override { return {.carries_sound = false}; }
    StepReport step(const Params<D>& params, Real dt, State<D>& state,
                    StepContext<D>& context) override;
    void update_fields(const Params<D>& params, State<D>& state, StepContext<D>& context) override;
    // The warm start's stiffnesses follow their particles; the other arrays
    // are recomputed every step.
    void permute(std::span<const std::uint32_t> order) override {
        for (std::vector<Real>* kept : kept_)
            if (kept->size() == order.size())
                sph::permute(*kept, order, permute_scratch_);
    }
    std::span<std::vector<Real>* const> kept_arrays() override { return kept_; }

    // Mean compression, in percent, the last density solve ended with.
    Real last_density_error_pct() const { return last_density_error_pct_; }

  private:
    enum class Target { divergence, density };
    template <class Kernel>
    void prepare(const Params<D>& params, const Kernel& kernel, StepContext<D>& context,
                 State<D>& state);
    int solve(const Params<D>& params, Real dt, Target target, StepContext<D>& context,
              State<D>& state);
    // Corrects placed_velocity_ (and its floats) with stiffness_.
    void correct_velocities(const State<D>& state);
    // state.acceleration += the walls' hydrostatic pressure (solver.wall_pressure).
    void add_wall_weight(const Params<D>& params, const StepContext<D>& context,
                         State<D>& state) const;
    // Halvings of a step at most: dt / 16.
    static constexpr int max_splits = 4;

    KernelKind kernel_;
    Real last_density_error_pct_ = 0;
    // Arrays this solver alone needs, sized to the particles; they live here,
    // not in State. Those of a step are in the slices' order (by place,
    // slice_row_ below), so that the loops over a slice's particles read
    // them whole; the kept ones are in the particles' order.
    // (units in dfsph.cpp)
    std::vector<Real> factor_;                         // 1 / S_i
    std::vector<Real> stiffness_;                      // s_i of this iteration
    std::vector<Real> stiffness_sum_;                  // s_i summed over the density solve
    std::vector<Real> divergence_sum_;                 // s_i summed over the divergence solve
    std::array<std::vector<Real>, D> placed_velocity_; // v_i during a solve, by component
    std::vector<Real> compression_;  // (rho_i - rho0) / dt in the density solve, else 0
    std::vector<Real> halo_scratch_; // s_i in the particles' order, over ranks
    std::vector<Real> previous_stiffness_, previous_divergence_; // last step's sums (kept)
    const std::array<std::vector<Real>*, 2> kept_{&previous_stiffness_, &previous_divergence_};
    Real previous_dt_ = 0;
    std::vector<Real> permute_scratch_;
    std::vector<Real> source_;                   // the compression rate to remove
    std::vector<Real> next_sum_;                 // the summed s_i after this iteration
    std::vector<Vec<D>> velocity_at_start_;      // to restart a diverging solve
    std::vector<Vec<D>> velocity_at_step_start_; // to redo a step in halves
    // The fluid pairs as the iterations read them: in slices of
    // slice_lanes consecutive particles (SELL-C, Kreutzer et al. 2014,
    // "A unified sparse matrix data format for efficient general sparse
    // matrix-vector multiplication on modern processors with wide SIMD
    // units"), column c of a slice holding each particle's c-th pair, the
    // rows shorter than the slice's longest padded with g = 0. A loop over
    // a slice's columns then sums all its particles' rows at once, lane by
    // lane: no sum across a register, no loop ending at each row (a row of
    // about 30 pairs ended in a mispredicted branch), and a column's g_ij
    // are whole-register loads; only v_j (s_j) are gathered. In floats: the
    // rounding (1e-7) is far below the solves' tolerances, and both passes
    // read the same g_ij, so the operator stays symmetric. Per-particle
    // sums and the state stay in double.
    // Rows in a slice are sorted longest first within windows of
    // window_slices slices (SELL-C-sigma, the same paper), so that a slice
    // holds rows of about one length: on SPlisHSPlasH's dam break the
    // padding is 6.5% of the entries, against 15-23% with the rows in
    // particle order (larger windows measured no faster: the rows of a
    // slice then lie farther apart).
    // In 2D, whose rows are short, the sort cost more than it saved (the
    // 2D water dam break 3% slower): there a slice is its own window.
    static constexpr std::size_t window_slices = D == 3 ? 4 : 1;
    std::vector<std::uint32_t> slice_start_; // first column of each slice, then the end
    std::vector<std::uint32_t> slice_row_;   // the particle at each place (lane of a slice)
    std::vector<std::uint32_t> slice_place_; // each particle's place: j in slice_index_ is one
    std::vector<std::uint32_t> slice_index_; // j's place, per column and lane
    std::array<std::vector<float>, D> slice_gradient_; // g_ij = m grad W_ij, by component
    // Quads: four floats a particle, gathered whole (gather_quads in dfsph.cpp); by place.
    std::vector<float> velocity_f_;  // (v_i, 0), rounded after each change
    std::vector<float> stiffness_f_; // s_i of this iteration, rounded
    std::vector<float> position_f_;  // (x_i - the domain's corner, rho_i), for the viscosities
    template <bool artificial, bool laminar>
    void add_fluid_viscosities(const MonaghanTerm<float>& Pi, const MorrisViscosity::Single& morris,
                               State<D>& state) const;
    // state.velocity into placed_velocity_ and velocity_f_, and back.
    void load_velocities(const State<D>& state);
    void store_velocities(State<D>& state) const;
    // The slices as the pair loops read them: pointers, local to a loop
    // (through `this` GCC 12 keeps a loop scalar).
    struct SliceView {
        const std::uint32_t* columns;         // slice_start_
        const std::uint32_t* row;             // slice_row_
        const std::uint32_t* index;           // slice_index_
        std::array<const float*, D> gradient; // slice_gradient_
        const float* velocity;                // velocity_f_, quads
        // A slice's entries: [first_entry, end_entry) in steps of slice_lanes.
        std::size_t first_entry(std::size_t slice) const {
            return std::size_t(columns[slice]) * slice_lanes;
        }
        std::size_t end_entry(std::size_t slice) const {
            return std::size_t(columns[slice + 1]) * slice_lanes;
        }
    };
    SliceView slice_view() const;
    std::vector<Vec<D>> wall_gradient_; // rho0 V_b grad W_ib per wall pair
    std::vector<Real> wall_motion_;     // sum_b w_ib . v_b; 0 when no wall moves
    // W_i = sum_b w_ib: the walls' whole part in the rate and the
    // correction, since both take the wall particles' v and s from the
    // fluid particle (one read a particle, not one a wall pair, per iteration).
    std::array<std::vector<Real>, D> wall_sum_; // by component
};

} // namespace sph
