#include "render/render_sink.hpp"

#include "io/particle_export.hpp"

#include <memory>

namespace sph {
namespace {

// Frames waiting for the encoder: two keep it busy while the next frame is
// simulated, and bound the memory held (8 MiB a frame at 1920x1080).
constexpr std::size_t encoder_queue_frames = 2;

} // namespace

RenderSink::RenderSink(std::unique_ptr<GlContext> context, const RenderSettings& settings,
                       std::filesystem::path png_folder, std::filesystem::path mp4_path, double fps,
                       const Mp4Options& mp4_options, EncodeThread encode)
    : context_(std::move(context)), renderer_(settings), png_folder_(std::move(png_folder)) {
    if (!png_folder_.empty()) {
        std::filesystem::create_directories(png_folder_);
        png_ = std::make_unique<PngWriterThread>();
    }
    if (!mp4_path.empty())
        mp4_ = std::make_unique<Mp4WriterThread>(mp4_path, settings.width, settings.height, fps,
                                                 mp4_options, encoder_queue_frames, encode);
}

void RenderSink::write(const Snapshot& frame) {
    FrameCost cost;
    // Shared by both writers, which only read it: no copy.
    const auto image = std::make_shared<const Image>(renderer_.render(frame));
    cost.render_s = renderer_.last_timings().draw_seconds;
    cost.readback_s = renderer_.last_timings().readback_seconds;
    costs_.push_back(cost);
    if (mp4_)
        mp4_->submit(image);
    if (png_)
        png_->submit(png_folder_ / (frame_stem(frame.frame) + ".png"), image);
}

std::vector<FrameCost> RenderSink::costs() const {
    std::vector<FrameCost> costs = costs_;
    if (const auto times = encode_times()) {
        for (std::size_t k = 0; k < costs.size(); ++k) {
            if (k < times->frame_seconds.size())
                costs[k].encode_s = times->frame_seconds[k];
            if (k < times->frame_wait_seconds.size())
                costs[k].encode_wait_s = times->frame_wait_seconds[k];
        }
    }
    return costs;
}

std::optional<Mp4WriterThread::Times> RenderSink::encode_times() const {
    if (!mp4_)
        return std::nullopt;
    return mp4_->times();
}

void RenderSink::finish() {
    // Both run even if one fails, so the video is finalised whatever happens.
    std::exception_ptr error;
    if (png_) {
        try {
            png_->finish();
        } catch (...) {
            error = std::current_exception();
        }
    }
    if (mp4_) {
        try {
            mp4_->finish();
        } catch (...) {
            if (!error)
                error = std::current_exception();
        }
    }
    if (error)
        std::rethrow_exception(error);
}

} // namespace sph
