#pragma once
// `wcsph`: weakly compressible SPH after Becker & Teschner 2007, "Weakly
// compressible SPH for free surface flows": the Tait equation of state, the
// symmetric pressure force, Monaghan's artificial viscosity, and walls of
// boundary particles (Akinci et al. 2012). The stiffness K (material.bulk_modulus)
// sets the sound speed c = sqrt(K / rho0); density errors scale like (v / c)^2.

#include "sph/density_diffusion.hpp"
#include "sph/equation_of_state.hpp"
#include "sph/single_precision/single_passes.hpp"
#include "sph/solvers/explicit_solver.hpp"
#include "sph/wall_pressure.hpp"

#include <array>
#include <memory>
#include <span>
#include <vector>

namespace sph {

// The single-precision passes are wcsph's; it keeps solver.artificial_viscosity.
inline constexpr SolverCapabilities wcsph_capabilities{.name = "wcsph",
                                                       .kind = SolverKind::wcsph,
                                                       .single_precision = true,
                                                       .default_artificial_viscosity = true};

template <int D>
class WcsphSolver final : public ExplicitSolver<D> {
  public:
    // `cell_skin`: params.cell_skin > 0, the single passes' cells kept
    // over steps (single_passes.hpp, CellSkin).
    WcsphSolver(KernelKind kernel, bool cell_skin) : kernel_(kernel), cell_skin_(cell_skin) {}
    std::string_view name() const override { return "wcsph"; }
    // Tait's sound speed grows as (rho / rho0)^3: a compressed start needs
    // far smaller steps than c0 suggests.
    TimeStepModel time_step_model() const override {
        return {.carries_sound = true, .sound_speed_exponent = 3};
    }
    void update_fields(const Params<D>& params, State<D>& state, StepContext<D>& context) override;
    Real compression_energy(const Params<D>& params, Real rho) const override {
        return compression_energy_tait(params, rho);
    }
    // With cell_skin, where the cells were made follows the particles (and
    // travels with them over MPI ranks), so that every rank makes the cells
    // one process keeps: the same bits on any number of ranks.
    void permute(std::span<const std::uint32_t> order) override;
    std::span<std::vector<Real>* const> kept_arrays() override {
        return cell_skin_ ? std::span<std::vector<Real>* const>(kept_)
                          : std::span<std::vector<Real>* const>{};
    }

  protected:
    void compute_accelerations(const Params<D>& params, State<D>& state,
                               StepContext<D>& context) override;
    bool carries_fields(const Params<D>& params) const override {
        return params.density_diffusion > 0;
    }
    void advance_carried(const Params<D>& params, Real dt, State<D>& state,
                         StepContext<D>& context) override;

  private:
    // The single-precision passes and their buffers, made at their first
    // use for the processor's widest variant.
    SinglePasses<D>& single_passes() {
        if (!single_)
            single_ = make_single_passes<D>();
        return *single_;
    }

    // The cells' skin for this step's density pass: the positions the
    // cells are made at, made again once a particle has moved half the
    // skin from its own, or when the particles are others.
    CellSkin<D> cell_skin(const Params<D>& params, const State<D>& state, StepContext<D>& context);

    KernelKind kernel_;
    bool cell_skin_ = false;
    // Where the cells were made, a particle's by component (kept arrays are
    // of Real), and the same as points for the passes.
    std::array<std::vector<Real>, D> made_at_;
    std::array<std::vector<Real>*, D> kept_ = [this] {
        std::array<std::vector<Real>*, D> kept;
        for (int a = 0; a < D; ++a)
            kept[std::size_t(a)] = &made_at_[std::size_t(a)];
        return kept;
    }();
    std::vector<Vec<D>> made_at_points_;
    std::vector<Real> permute_scratch_;
    // Whether the passes' cells are those made at made_at_ in the current
    // memory order (one process: a step may keep them).
    bool cells_made_ = false;
    // The skin of the cells made last (m; 0: made where the particles
    // were, for one step), and the steps they have served.
    Real skin_width_ = 0;
    int steps_on_cells_ = 0;
    std::vector<Real> pressure_term_; // p / rho^2 per particle, scratch
    // solver.density_diffusion: D rho / Dt, kg/(m^D s), and the renormalised
    // density gradients (sph/density_diffusion.hpp), scratch of each step.
    std::vector<Real> density_rate_;
    ContinuityScratch<D> continuity_;
    WallPressureScratch wall_pressure_; // solver.wall_pressure extrapolated
    std::unique_ptr<SinglePasses<D>> single_;
};

} // namespace sph
