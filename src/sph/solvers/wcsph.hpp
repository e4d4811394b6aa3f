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

#include <memory>
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
    explicit WcsphSolver(KernelKind kernel) : kernel_(kernel) {}
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

    KernelKind kernel_;
    std::vector<Real> pressure_term_; // p / rho^2 per particle, scratch
    // solver.density_diffusion: D rho / Dt, kg/(m^D s), and the renormalised
    // density gradients (sph/density_diffusion.hpp), scratch of each step.
    std::vector<Real> density_rate_;
    ContinuityScratch<D> continuity_;
    WallPressureScratch wall_pressure_; // solver.wall_pressure extrapolated
    std::unique_ptr<SinglePasses<D>> single_;
};

} // namespace sph
