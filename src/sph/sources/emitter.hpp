#pragma once
// An emitter: a stream of fluid entering through a box at a given velocity,
// between a start and an end time. The box is filled on the fluid's lattice
// (as a block is) and emitted whole, one batch every d / |v| seconds, d the
// box's thickness along v, so consecutive batches join without gaps or
// overlaps: the flow rate is the batch's particles times |v| / d. A batch due
// at t_k but emitted at the start of a step at t > t_k is placed where it
// would be by then, x + v (t - t_k), so the stream stays evenly spaced
// whatever the time step. Particles in the inlet zone (the box and one
// thickness downstream of it) move at the inlet's velocity at the start of
// every step, as in the inflow buffers of Federico et al. 2012: without it the
// pressure of the fluid ahead slows the last batches down and the next one
// lands on them. A batch that would put a particle within half a
// spacing of fluid already there (the inlet is flooded) waits, as a real inlet against back
// pressure would, instead of stacking particles on others: the schedule moves on from when it is
// free (blocked_seconds() says how long it waited). New particles get the next ids; every array of
// the state grows with them (State::resize), and the solvers size their own arrays from the state
// each step.

#include "sph/sources/source.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace sph {

template <int D>
class Emitter final : public Source<D> {
  public:
    // `sites`: the box's lattice points; `thickness`: its extent along v (m).
    Emitter(const Box<D>& box, Real spacing, std::vector<Vec<D>> sites, const Vec<D>& velocity,
            Real thickness, Real start, Real end)
        : box_(box), clearance_(spacing / 2), sites_(std::move(sites)), velocity_(velocity),
          interval_(thickness / glm::length(velocity)), start_(start), end_(end) {
        // The scene's checks guarantee it; an empty box would loop forever.
        if (sites_.empty() || !(interval_ > 0))
            throw std::invalid_argument("an emitter needs a box holding particles and a velocity");
    }

    std::string_view name() const override { return "emitters"; }
    std::size_t bytes() const override { return sites_.capacity() * sizeof(Vec<D>); }

    void emit(const Params<D>&, Real time, State<D>& state, Collective* ranks) override {
        if (time >= start_ && time < end_ + interval_)
            drive_inlet_zone(state);
        // Batches due by `time` (a little slack for rounding of t).
        while (true) {
            const Real due = start_ + Real(emitted_) * interval_;
            if (due > time + 1e-12 * interval_ || due >= end_)
                return;
            const bool flooded_here = flooded(state);
            if (ranks ? ranks->any(flooded_here) : flooded_here) {
                blocked_ += time - due;
                start_ += time - due;
                return;
            }
            ++emitted_;
            // Ids are 0 .. n-1 over all particles; over ranks the batch goes
            // where the memory order ends, and every rank counts it.
            const std::size_t first_id = ranks ? ranks->total_particles() : state.size();
            if (ranks)
                ranks->appended(sites_.size());
            if (ranks && !ranks->holds_end())
                continue;
            const std::size_t first = state.size();
            state.resize(first + sites_.size());
            for (std::size_t k = 0; k < sites_.size(); ++k) {
                const std::size_t i = first + k;
                state.position[i] = sites_[k] + (time - due) * velocity_;
                state.velocity[i] = velocity_;
                state.acceleration[i] = Vec<D>(0);
                state.density[i] = 0;
                state.pressure[i] = 0;
                state.id[i] = static_cast<std::uint32_t>(first_id + k);
            }
        }
    }

    Real speed() const override { return glm::length(velocity_); }
    // Particles per second while it runs.
    Real rate() const { return Real(sites_.size()) / interval_; }
    std::size_t batch() const { return sites_.size(); }
    Real blocked_seconds() const { return blocked_; }

  private:
    void drive_inlet_zone(State<D>& state) const {
        Box<D> zone = box_;
        const Vec<D> downstream = interval_ * velocity_; // one thickness along v
        for (int a = 0; a < D; ++a) {
            zone.min[a] = std::min(box_.min[a], box_.min[a] + downstream[a]);
            zone.max[a] = std::max(box_.max[a], box_.max[a] + downstream[a]);
        }
        for (std::size_t i = 0; i < state.size(); ++i)
            if (zone.contains(state.position[i]))
                state.velocity[i] = velocity_;
    }

    bool flooded(const State<D>& state) const {
        Box<D> near = box_;
        near.min -= Vec<D>(clearance_);
        near.max += Vec<D>(clearance_);
        for (const auto& x : state.position) {
            if (!near.contains(x))
                continue;
            for (const auto& site : sites_)
                if (squared_length<D>(x - site) < clearance_ * clearance_)
                    return true;
        }
        return false;
    }

    Box<D> box_;
    Real clearance_;
    std::vector<Vec<D>> sites_;
    Vec<D> velocity_;
    Real interval_, start_, end_;
    std::size_t emitted_ = 0;
    Real blocked_ = 0;
};

} // namespace sph
