#pragma once
// What the parts of a simulation ask of the other processes when its
// particles are shared out over several (MPI ranks, src/parallel/): each
// process holds a contiguous run of the particles in memory order, rank 0
// the first. Nothing here knows about MPI; in one process there is no
// Collective (a null pointer) and each question answers itself.

#include "sph/vec.hpp"

#include <cstddef>
#include <cstdint>
#include <span>

namespace sph {

class Collective {
  public:
    virtual ~Collective() = default;
    // Whether any process says true.
    virtual bool any(bool mine) = 0;
    // Each entry the largest over the processes, in place (a maximum has
    // the same bits whatever the order it is taken in).
    virtual void max(std::span<Real> values) = 0;
    // The process whose `key` is lowest (the first of those, by rank):
    // e.g. which found a problem in the earliest of an ordered list of checks.
    virtual int lowest(int key) = 0;
    // `bytes` from process `from` to every process.
    virtual void broadcast(std::span<std::byte> bytes, int from) = 0;
    // This process's rank (0 in one process).
    virtual int rank() const = 0;
    // Particles over all processes.
    virtual std::size_t total_particles() const = 0;
    // `count` particles were appended at the end of the memory order (every
    // process says so, the one that holds the end appending them).
    virtual void appended(std::size_t count) = 0;
    // Whether this process holds the end of the memory order, where new
    // particles are appended.
    virtual bool holds_end() const = 0;
};

} // namespace sph
