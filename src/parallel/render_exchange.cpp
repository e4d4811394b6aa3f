#include "parallel/render_exchange.hpp"

#include "parallel/world.hpp"

#include <array>
#include <climits>
#include <mpi.h>
#include <stdexcept>
#include <vector>

namespace sph::parallel {

namespace {

constexpr int colour_tag = 1, depth_tag = 2;

int message_count(std::size_t count) {
    if (count > std::size_t(INT_MAX))
        throw std::runtime_error("a rank's layer is too large for one MPI message");
    return int(count);
}

class RenderExchange final : public RankCompositing {
  public:
    explicit RenderExchange(std::size_t from_particles) : from_particles_(from_particles) {
        MPI_Comm_dup(MPI_COMM_WORLD, &comm_);
        MPI_Comm_rank(comm_, &rank_);
        MPI_Comm_size(comm_, &ranks_);
    }
    ~RenderExchange() override {
        MPI_Waitall(int(sends_.size()), sends_.data(), MPI_STATUSES_IGNORE);
        MPI_Comm_free(&comm_);
    }
    RenderExchange(const RenderExchange&) = delete;
    RenderExchange& operator=(const RenderExchange&) = delete;

    int rank() const override { return rank_; }
    int ranks() const override { return ranks_; }
    bool by_depth(std::size_t particles) const override { return particles >= from_particles_; }

    void from_leader(std::span<std::byte> bytes) override {
        MPI_Bcast(bytes.data(), message_count(bytes.size()), MPI_BYTE, 0, comm_);
    }

    void min_over_ranks(std::span<std::uint32_t> values) override {
        MPI_Allreduce(MPI_IN_PLACE, values.data(), message_count(values.size()), MPI_UINT32_T,
                      MPI_MIN, comm_);
    }

    void sum_on_leader(std::span<std::uint64_t> counts) override {
        if (rank_ == 0)
            MPI_Reduce(MPI_IN_PLACE, counts.data(), message_count(counts.size()), MPI_UINT64_T,
                       MPI_SUM, 0, comm_);
        else
            MPI_Reduce(counts.data(), nullptr, message_count(counts.size()), MPI_UINT64_T, MPI_SUM,
                       0, comm_);
    }

    RankLayerPixels& layer_to_send() override {
        // The previous frame's layer has left before it is overwritten.
        MPI_Waitall(int(sends_.size()), sends_.data(), MPI_STATUSES_IGNORE);
        return outgoing_;
    }

    void send_layer() override {
        MPI_Isend(outgoing_.colour.data(), message_count(outgoing_.colour.size()), MPI_UINT8_T, 0,
                  colour_tag, comm_, &sends_[0]);
        MPI_Isend(outgoing_.depth_bits.data(), message_count(outgoing_.depth_bits.size()),
                  MPI_UINT32_T, 0, depth_tag, comm_, &sends_[1]);
    }

    void receive_layers(std::size_t samples,
                        const std::function<void(int, const RankLayerPixels&)>& take) override {
        const std::size_t others = std::size_t(ranks_ - 1);
        incoming_.resize(others);
        receives_.assign(2 * others, MPI_REQUEST_NULL);
        for (std::size_t k = 0; k < others; ++k) {
            RankLayerPixels& layer = incoming_[k];
            layer.colour.resize(samples * 4);
            layer.depth_bits.resize(samples);
            const int from = int(k) + 1;
            MPI_Irecv(layer.colour.data(), message_count(layer.colour.size()), MPI_UINT8_T, from,
                      colour_tag, comm_, &receives_[2 * k]);
            MPI_Irecv(layer.depth_bits.data(), message_count(layer.depth_bits.size()), MPI_UINT32_T,
                      from, depth_tag, comm_, &receives_[2 * k + 1]);
        }
        // Each layer as soon as both its parts are in: its upload overlaps
        // the others' transfer.
        std::vector<int> parts_in(others, 0), done(receives_.size());
        for (std::size_t taken = 0; taken < others;) {
            int count = 0;
            MPI_Waitsome(int(receives_.size()), receives_.data(), &count, done.data(),
                         MPI_STATUSES_IGNORE);
            for (int i = 0; i < count; ++i) {
                const std::size_t k = std::size_t(done[std::size_t(i)]) / 2;
                if (++parts_in[k] == 2) {
                    take(int(k) + 1, incoming_[k]);
                    ++taken;
                }
            }
        }
    }

  private:
    std::size_t from_particles_;
    MPI_Comm comm_ = MPI_COMM_NULL;
    int rank_ = 0, ranks_ = 1;
    RankLayerPixels outgoing_;
    std::array<MPI_Request, 2> sends_{MPI_REQUEST_NULL, MPI_REQUEST_NULL};
    std::vector<RankLayerPixels> incoming_;
    std::vector<MPI_Request> receives_;
};

} // namespace

std::unique_ptr<RankCompositing> make_render_exchange(std::size_t from_particles) {
    if (size() < 2)
        return nullptr;
    return std::make_unique<RenderExchange>(from_particles);
}

} // namespace sph::parallel
