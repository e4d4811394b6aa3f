#pragma once
// What depth compositing over MPI ranks (render/depth_composite.hpp) needs
// from the ranks, without GL or MPI: the layer a rank sends, and the
// transport, which src/parallel/render_exchange.cpp implements over MPI.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace sph {

// render.mpi_composite = auto composites a frame by depth from this many
// particles on; none: never. Measured (tests/bench/mpi_composite.sh,
// docs/mpi.md "Rendering over ranks"): on 2 ranks of a 2-core machine depth
// won for a gas from 100k particles and a 1M fluid at 640x360, and lost for
// a fluid at 1280x720 up to 1M and below 100k; a particle count cannot tell
// a fluid from a gas (10x more spheres drawn), so auto gathers.
inline constexpr std::optional<std::size_t> auto_depth_from_particles = std::nullopt;

// A sample no sphere of the rank covers.
inline constexpr std::uint32_t empty_sample = 0xffffffffu;
// The depth bits' flag for a sphere drawn on a triangle (the second group);
// the depth is clamped to [0, 1], so below 2^30 as bits.
inline constexpr std::uint32_t triangle_group_bit = 0x40000000u;

// One rank's layer as it travels: every sample of the frame side by side,
// pixel (x, y)'s sample s at (x samples + s, y), rows bottom-up as GL has
// them.
struct RankLayerPixels {
    std::vector<std::uint8_t> colour;      // RGBA8
    std::vector<std::uint32_t> depth_bits; // depth float's bits | group, or empty_sample
};

// The transport between the ranks, implemented over MPI in src/parallel/
// (render_exchange.cpp); the renderer knows nothing of MPI.
class RankCompositing {
  public:
    virtual ~RankCompositing() = default;
    virtual int rank() const = 0;
    virtual int ranks() const = 0;
    // Whether a frame of `particles` particles is composited by depth (the
    // same answer on every rank), else drawn whole on rank 0.
    virtual bool by_depth(std::size_t particles) const = 0;
    // Every rank: rank 0's `bytes` (the frame's camera pose, which rank 0
    // alone, holding every particle, can fit).
    virtual void from_leader(std::span<std::byte> bytes) = 0;
    // Every rank: each value replaced by its minimum over the ranks.
    virtual void min_over_ranks(std::span<std::uint32_t> values) = 0;
    // Every rank: the counts summed over the ranks, into rank 0's.
    virtual void sum_on_leader(std::span<std::uint64_t> counts) = 0;
    // Ranks but 0: the buffer to read this frame's layer into (once the
    // previous frame's has been sent), then send it to rank 0.
    virtual RankLayerPixels& layer_to_send() = 0;
    virtual void send_layer() = 0;
    // Rank 0: every other rank's layer of `samples` samples as it arrives,
    // take(rank, layer).
    virtual void receive_layers(std::size_t samples,
                                const std::function<void(int, const RankLayerPixels&)>& take) = 0;
};

} // namespace sph
