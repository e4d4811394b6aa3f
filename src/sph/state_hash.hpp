#pragma once
// A fingerprint of a frame's particle state, written to stats.csv so a user
// can check that two runs gave the same bits (same scene, build and thread
// count, or any thread count: the solvers are deterministic).
//
// Each particle's exact bits (id, position, velocity, density) are
// hashed (FNV-1a, 64 bits) and the particle hashes summed, so the
// fingerprint does not depend on the order particles sit in memory. Pressure
// is left out: it follows from the density (seed, wcsph) or is an output of
// the last solve (dfsph), and a run computes it only when an output reads it
// (FrameFields), which must not change the fingerprint.

#include "sph/snapshot.hpp"

#include <bit>
#include <cstdint>

namespace sph {

inline std::uint64_t state_hash(const Snapshot& frame) {
    constexpr std::uint64_t offset = 0xcbf29ce484222325ull, prime = 0x100000001b3ull;
    const std::size_t n = frame.size();
    const int d = frame.dimension;
    std::uint64_t total = 0;
    for (std::size_t i = 0; i < n; ++i) {
        std::uint64_t h = offset;
        auto add = [&h](std::uint64_t word) {
            for (int byte = 0; byte < 8; ++byte) {
                h ^= (word >> (8 * byte)) & 0xffu;
                h *= prime;
            }
        };
        add(frame.id[i]);
        for (int a = 0; a < d; ++a) {
            add(std::bit_cast<std::uint64_t>(frame.position[i * d + a]));
            add(std::bit_cast<std::uint64_t>(frame.velocity[i * d + a]));
        }
        add(std::bit_cast<std::uint64_t>(frame.density[i]));
        total += h;
    }
    return total;
}

} // namespace sph
