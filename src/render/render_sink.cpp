#include "render/render_sink.hpp"

#include "output/particle_export.hpp"

#include <fmt/format.h>
#include <memory>

namespace sph {
namespace {

// Frames waiting for the encoder: two keep it busy while the next frame is
// simulated, and bound the memory held (8 MiB a frame at 1920x1080).
constexpr std::size_t encoder_queue_frames = 2;

// A frame with more of its drawn particles outside the colour range than
// this shows them in the map's end colours only: the range is likely wrong.
constexpr double outside_range_share = 0.05;

} // namespace

RenderSink::RenderSink(std::unique_ptr<GlContext> context, const RenderSettings& settings,
                       std::filesystem::path png_folder, std::filesystem::path mp4_path, double fps,
                       const Mp4Options& mp4_options, EncodeThread encode,
                       std::shared_ptr<FrameSurface> surface)
    : context_(std::move(context)), renderer_(settings, std::move(surface)),
      png_folder_(std::move(png_folder)) {
    if (!renderer_.font_warning().empty())
        warnings_.push_back(renderer_.font_warning());
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
    if (renderer_.last_composited()) {
        cost.composite_s = renderer_.last_composite_seconds();
        ++frames_composited_;
    }
    costs_.push_back(cost);
    poses_.push_back({frame.frame, double(frame.time), renderer_.last_pose()});
    check_range(frame);
    if (mp4_)
        mp4_->submit(image);
    if (png_)
        png_->submit(png_folder_ / (frame_stem(frame.frame) + ".png"), image);
}

void RenderSink::check_range(const Snapshot& frame) {
    const std::size_t drawn = renderer_.last_drawn();
    if (range_warned_ || drawn == 0)
        return;
    const double below = double(renderer_.last_below_range()) / double(drawn);
    const double above = double(renderer_.last_above_range()) / double(drawn);
    if (below + above <= outside_range_share)
        return;
    range_warned_ = true;
    const RenderSettings& s = renderer_.settings();
    const std::string from = s.range_key.empty()
                                 ? "the default from the scene's physics; render.range sets another"
                                 : "set by " + s.range_key;
    warnings_.push_back(
        fmt::format("frame {} (t = {:.3g} s): {:.0f}% of the drawn particles have a {} outside the "
                    "colour range [{:.4g}, {:.4g}] ({:.0f}% below, {:.0f}% above; {}), shown in "
                    "the map's end colours",
                    frame.frame, frame.time, 100 * (below + above), s.label, s.range[0], s.range[1],
                    100 * below, 100 * above, from));
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
