#pragma once
// Where a run's time goes, stage by stage (neighbour search, density, each
// effect, pressure solve, integration, ...), so that a user sees what each
// part of the step, and each effect the scene names, costs. A stage is timed
// by a scope object around its call; a stage that never runs never appears.
// The clock is read twice per stage and step: tens of nanoseconds against
// the microseconds a stage takes per particle.

#include <chrono>
#include <cstdint>
#include <string_view>
#include <vector>

namespace sph {

class StageTimes {
  public:
    struct Entry {
        std::string_view name; // a literal or an effect's name(): lives as long as the run
        double seconds = 0;
    };

    // Adds the time from its construction to its destruction to a stage.
    class Scope {
      public:
        Scope(StageTimes* times, std::string_view name)
            : times_(times), name_(name), start_(std::chrono::steady_clock::now()) {}
        Scope(const Scope&) = delete;
        Scope& operator=(const Scope&) = delete;
        ~Scope() {
            if (times_)
                times_->add(name_,
                            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_)
                                .count());
        }

      private:
        StageTimes* times_;
        std::string_view name_;
        std::chrono::steady_clock::time_point start_;
    };

    void add(std::string_view name, double seconds) {
        for (auto& e : entries_)
            if (e.name == name) {
                e.seconds += seconds;
                return;
            }
        entries_.push_back({name, seconds}); // once per stage and run
    }
    // Stages in the order they first ran.
    const std::vector<Entry>& entries() const { return entries_; }

  private:
    std::vector<Entry> entries_;
};

} // namespace sph
