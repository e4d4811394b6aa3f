#pragma once
// The `seed` solver: the model of the report sphclip grew from
// (../shared/seed/MODEL.md), kept faithful so results can be compared with it.

#include "sph/equation_of_state.hpp"
#include "sph/solvers/explicit_solver.hpp"

namespace sph {

// Reflecting walls only; the seed's kernel and viscosity term by default.
inline constexpr SolverCapabilities seed_capabilities{.name = "seed",
                                                      .kind = SolverKind::seed,
                                                      .wall_particles = false,
                                                      .default_kernel = KernelKind::seed,
                                                      .viscosity_model = ViscosityModel::seed};

// Its step (compute_accelerations, then the integrator of explicit_solver.hpp):
// neighbours, density, linear pressure, the seed's pair force, effects. With
// the seed's kernel and symplectic Euler it is the report's model exactly;
// another kernel replaces poly6 and spiky's gradient by its own.
template <int D>
class SeedSolver final : public ExplicitSolver<D> {
  public:
    explicit SeedSolver(KernelKind kernel = KernelKind::seed);
    std::string_view name() const override { return "seed"; }
    void update_fields(const Params<D>& params, State<D>& state, StepContext<D>& context) override;
    Real compression_energy(const Params<D>& params, Real rho) const override {
        return compression_energy_linear(params, rho);
    }

  protected:
    void compute_accelerations(const Params<D>& params, State<D>& state,
                               StepContext<D>& context) override;

  private:
    KernelKind kernel_;
};

// The seed's interaction force summed for every particle and divided by its
// density: state.acceleration = (1 / rho_i) sum_j f_ij, by the one pass the
// solver runs (pressure and viscous halves together), mu the viscosity
// (Pa.s). Exposed for tests.
template <int D>
void compute_seed_interaction(const Params<D>& params, Real mu, const NeighbourList& neighbours,
                              State<D>& state);

// f_ij / rho_i: the acceleration particle j gives particle i, mu the
// viscosity (Pa.s). Exposed for tests.
template <int D>
Vec<D> seed_pair_acceleration(const Params<D>& params, Real mu, const State<D>& state,
                              std::size_t i, std::size_t j);

// f_ij, the seed's force density on i from j. Exposed for tests.
template <int D>
Vec<D> seed_pair_force(const Params<D>& params, Real mu, const State<D>& state, std::size_t i,
                       std::size_t j);

} // namespace sph
