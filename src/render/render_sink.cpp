#include "render/render_sink.hpp"

#include "io/particle_export.hpp"

#include <chrono>

namespace sph {

RenderSink::RenderSink(std::unique_ptr<GlContext> context, const RenderSettings& settings,
                       std::filesystem::path png_folder, std::filesystem::path mp4_path, double fps,
                       const Mp4Options& mp4_options)
    : context_(std::move(context)), renderer_(settings), png_folder_(std::move(png_folder)) {
    if (!png_folder_.empty()) {
        std::filesystem::create_directories(png_folder_);
        png_ = std::make_unique<PngWriterThread>();
    }
    if (!mp4_path.empty())
        mp4_ = std::make_unique<Mp4Writer>(mp4_path, settings.width, settings.height, fps,
                                           mp4_options);
}

void RenderSink::write(const Snapshot& frame) {
    FrameCost cost;
    Image image = renderer_.render(frame);
    cost.render_s = renderer_.last_timings().draw_seconds;
    cost.readback_s = renderer_.last_timings().readback_seconds;
    const auto start = std::chrono::steady_clock::now();
    if (mp4_)
        mp4_->write(image);
    if (png_)
        png_->submit(png_folder_ / (frame_stem(frame.frame) + ".png"), std::move(image));
    cost.encode_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    costs_.push_back(cost);
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
    if (mp4_)
        mp4_->finish();
    if (error)
        std::rethrow_exception(error);
}

} // namespace sph
