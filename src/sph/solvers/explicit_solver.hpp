#pragma once
// What the explicit solvers (seed, wcsph) share: they compute accelerations
// from the state, and an integrator chosen by the scene moves the particles.
//   symplectic Euler (the seed's, first order):  a(x, v); v += dt a; x += dt v
//   velocity Verlet / leapfrog kick-drift-kick (second order, Verlet 1967):
//     v += dt/2 a;  x += dt v;  a(x, v);  v += dt/2 a
// Verlet's second half-kick uses the accelerations at the new positions, which
// the next step's first half-kick reuses: one force evaluation per step.

#include "sph/integrate.hpp"
#include "sph/solvers/solver.hpp"

namespace sph {

template <int D>
class ExplicitSolver : public Solver<D> {
  public:
    TimeStepModel time_step_model() const override { return {.carries_sound = true}; }
    // The accelerations a Verlet step starts from and a carried density;
    // the densities and pressures otherwise come from the positions first.
    StepInputs step_inputs(const Params<D>& params) const override {
        return {.acceleration = params.integrator == Integrator::verlet,
                .density = carries_fields(params),
                .pressure = false};
    }

    StepReport step(const Params<D>& params, Real dt, State<D>& state,
                    StepContext<D>& context) override {
        StepReport report;
        if (params.integrator == Integrator::verlet) {
            if (!accelerations_current_ || state.size() != accelerations_for_)
                compute_accelerations(params, state, context);
            {
                auto timed = context.time(Stage::integration);
                kick(dt / 2, state);
                drift(dt, state);
            }
            // The last guard: the boundaries keep the particles out.
            report.obstacle_pushes = context.last_guard(context.start_time + dt, state);
            // The forces at the new positions see the paddles where they are then.
            context.place_boundaries(context.start_time + dt);
            compute_accelerations(params, state, context);
            auto timed = context.time(Stage::integration);
            kick(dt / 2, state);
            accelerations_current_ = true;
            accelerations_for_ = state.size();
        } else {
            compute_accelerations(params, state, context);
            if (carries_fields(params)) {
                {
                    auto timed = context.time(Stage::integration);
                    kick(dt, state);
                }
                // Carried fields advance with the new velocities, as the
                // positions do (symplectic Euler for them too).
                advance_carried(params, dt, state, context);
                auto timed = context.time(Stage::integration);
                drift(dt, state);
            } else {
                auto timed = context.time(Stage::integration);
                integrate_symplectic_euler(dt, state);
            }
            // The last guard: the boundaries keep the particles out.
            report.obstacle_pushes = context.last_guard(context.start_time + dt, state);
        }
        return report;
    }

    // Whether the state's accelerations are those of its positions and
    // velocities, as after a Verlet step of `size` particles: a partition
    // (sph/partition.hpp) steps a different subset of particles each step,
    // so it says what a step of the whole state would have found.
    void set_accelerations_current(bool current, std::size_t size) {
        accelerations_current_ = current;
        accelerations_for_ = size;
    }

    // What a Verlet step whose accelerations are not current does first:
    // the accelerations at the current state, then current. A partition
    // calls it over a halo of its own before the step, so that the step's
    // drift is bounded by them as any other step's is.
    void refresh_accelerations(const Params<D>& params, State<D>& state, StepContext<D>& context) {
        compute_accelerations(params, state, context);
        set_accelerations_current(true, state.size());
    }

  protected:
    // state.acceleration = every force of the model at the current state.
    virtual void compute_accelerations(const Params<D>& params, State<D>& state,
                                       StepContext<D>& context) = 0;
    // Fields the solver carries from step to step besides x and v (wcsph's
    // continuity density), advanced by dt after the kick and before the
    // drift: their rates from the step's positions and neighbour lists and
    // the new velocities. Taken from the old velocities, the density and
    // the velocity would both step forward from the old state, and the sound
    // waves between them grow at every step (explicit Euler on an
    // oscillator). Symplectic Euler only (the scene checks it).
    virtual bool carries_fields(const Params<D>& /*params*/) const { return false; }
    virtual void advance_carried(const Params<D>& /*params*/, Real /*dt*/, State<D>& /*state*/,
                                 StepContext<D>& /*context*/) {}

  private:
    bool accelerations_current_ = false;
    std::size_t accelerations_for_ = 0;
};

} // namespace sph
