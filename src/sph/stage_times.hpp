#pragma once
// Where a run's time goes, stage by stage (neighbour search, density, each
// effect, pressure solve, integration, ...), so that a user sees what each
// part of the step, and each part the scene declares, costs. A stage is timed
// by a scope object around its call; a stage that never runs never appears.
// The clock is read twice per stage and step: tens of nanoseconds against
// the microseconds a stage takes per particle.
//
// A row of the stage table is one of two kinds:
// - a stage of the algorithm, from the one table below (Stage);
// - a part the scene declares, an effect, a boundary or a particle source,
//   under the key that names it in the scene (its name()): every part the
//   scene declares has a row, and no other part has one. A part a solver
//   computes inside one of its own stages (a viscosity joining wcsph's
//   pressure pass) has a row that says which, its time being that stage's.

#include "sph/wall_clock.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

namespace sph {

enum class Stage : std::uint8_t {
    // The step (Simulation::step_by, the solvers' step).
    neighbour_search,    // the fluid's neighbours
    boundary_neighbours, // each fluid particle's boundary particles
    density,             // dfsph: with the pairs' gradients and the solves' factors, in one pass
    pressure,            // explicit solvers: the equation of state, the pressure force
    density_rate,        // wcsph's carried density: its rate and delta-SPH's diffusion
    wall_pressure,       // wcsph: the walls' pressure extrapolated from the fluid
    viscosities,         // dfsph: Monaghan's and Morris's viscosities in one pass
    divergence_solve,    // dfsph
    pressure_solve,      // dfsph
    integration,
    time_step, // the stability conditions
    watchdog,  // the checks after a step, the state saved for a retry
    reorder,   // the spatial sort
    // Over MPI ranks (src/parallel/): choosing a rank's halo and copying its
    // particles, the halo's densities from their owners mid-step, the
    // whole state gathered at a frame.
    rank_halo,
    halo_exchange,
    rank_gather,
    // Around the step (the run command).
    frame_statistics,
    render,
    // Over MPI ranks with depth compositing (render/depth_composite.hpp),
    // rank 0's part of drawing: its own layer, the others' received and
    // written into the frame (the rest of the frame is `render`).
    composite,
    readback,
    encode_wait,
    output, // stats, exports, handing frames to the writers
    encode, // on the encoder's thread
    count
};

// The names the stage table and run.json's `stages` print, by Stage.
inline constexpr std::array<std::string_view, std::size_t(Stage::count)> stage_names{
    "neighbour search",
    "boundary neighbours",
    "density",
    "pressure",
    "density rate",
    "wall pressure",
    "viscosities",
    "divergence solve",
    "pressure solve",
    "integration",
    "time step",
    "watchdog",
    "reorder",
    "rank halo",
    "halo exchange",
    "rank gather",
    "frame statistics",
    "render",
    "composite",
    "readback",
    "encode wait",
    "output",
    "encode"};

constexpr std::string_view stage_name(Stage stage) {
    return stage_names[std::size_t(stage)];
}

// What a row is about: a Stage, or a part of the scene by its key.
class StageName {
  public:
    constexpr StageName(Stage stage) : text_(stage_name(stage)) {} // NOLINT: implicit on purpose
    // An effect, boundary or source: its name() is its scene key, and lives
    // as long as the part (the run).
    template <class Part>
    static StageName of(const Part& part) {
        return StageName(part.name());
    }
    std::string_view text() const { return text_; }

  private:
    explicit constexpr StageName(std::string_view text) : text_(text) {}
    std::string_view text_;
};

class StageTimes {
  public:
    struct Entry {
        std::string_view name; // a Stage's or a part's name: lives as long as the run
        double seconds = 0;
        // A part computed inside that stage, whose time holds it (seconds 0).
        std::optional<Stage> within;
    };

    // Adds the time from its construction to its destruction to a stage.
    class Scope {
      public:
        Scope(StageTimes* times, StageName name)
            : times_(times), name_(name), start_(Clock::now()) {}
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;
        ~Scope() {
            if (times_)
                times_->add(name_, seconds_since(start_));
        }

      private:
        StageTimes* times_;
        StageName name_;
        Clock::time_point start_;
    };

    void add(StageName name, double seconds) { entry(name).seconds += seconds; }
    // `part` was computed inside `stage` (and timed as part of it).
    void add_within(StageName part, Stage stage) { entry(part).within = stage; }
    // Stages in the order they first ran.
    const std::vector<Entry>& entries() const { return entries_; }

  private:
    Entry& entry(StageName name) {
        for (auto& e : entries_)
            if (e.name == name.text())
                return e;
        return entries_.emplace_back(Entry{name.text(), 0, std::nullopt}); // once per stage and run
    }

    std::vector<Entry> entries_;
};

} // namespace sph
