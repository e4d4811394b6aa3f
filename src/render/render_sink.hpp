#pragma once
// The frame sink that makes pictures: renders each frame in the headless GL
// context, writes frames/frame_NNNNN.png (on a worker thread) and feeds the
// same pixels to the MP4 encoder.

#include "io/frame_sink.hpp"
#include "io/mp4_writer.hpp"
#include "io/png_io.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"

#include <filesystem>
#include <memory>
#include <vector>

namespace sph {

struct FrameCost {
    double render_s = 0, readback_s = 0, encode_s = 0;
};

class RenderSink final : public FrameSink {
  public:
    // `png_folder` empty: no PNGs; `mp4_path` empty: no video.
    RenderSink(std::unique_ptr<GlContext> context, const RenderSettings& settings,
               std::filesystem::path png_folder, std::filesystem::path mp4_path, double fps,
               const Mp4Options& mp4_options);
    void write(const Snapshot& frame) override;
    // Waits for the PNGs and finalises the video, also after an early stop.
    void finish() override;

    const GlInfo& gl_info() const { return context_->info(); }
    const std::vector<FrameCost>& costs() const { return costs_; }

  private:
    std::unique_ptr<GlContext> context_;
    FrameRenderer renderer_;
    std::filesystem::path png_folder_;
    std::unique_ptr<PngWriterThread> png_;
    std::unique_ptr<Mp4Writer> mp4_;
    std::vector<FrameCost> costs_;
};

} // namespace sph
