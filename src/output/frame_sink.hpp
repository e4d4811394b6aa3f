#pragma once
// Everything that consumes frames (stats, particle exports, and later images
// and video) implements this interface; the run loop hands each frame to
// every sink the command line asked for.

#include "sph/snapshot.hpp"

namespace sph {

class FrameSink {
  public:
    virtual ~FrameSink() = default;
    virtual void write(const Snapshot& frame) = 0;
    // The optional fields it reads (none by default).
    virtual FrameFields fields() const { return {.pressure = false}; }
    // Called once after the last frame, also when a run stops early.
    virtual void finish() {}
};

} // namespace sph
