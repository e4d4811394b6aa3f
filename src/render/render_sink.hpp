#pragma once
// The frame sink that makes pictures: renders each frame in the headless GL
// context, writes frames/frame_NNNNN.png and feeds the same pixels to the MP4
// encoder, each on a worker thread of its own. Rendering stays on the calling
// thread, which owns the GL context.

#include "output/frame_sink.hpp"
#include "output/mp4_writer_thread.hpp"
#include "output/png_io.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sph {

// Seconds one frame cost. render_s, readback_s and encode_wait_s are the
// calling thread's; encode_s is the encoder's, which overlaps the caller's
// work when it runs on its worker thread.
struct FrameCost {
    double render_s = 0, readback_s = 0;
    double composite_s = 0;   // over MPI ranks, by depth: part of render_s
    double encode_s = 0;      // colour conversion, libx264, muxing
    double encode_wait_s = 0; // the caller blocked on a full encoder queue
};

class RenderSink final : public FrameSink {
  public:
    // `png_folder` empty: no PNGs; `mp4_path` empty: no video. `encode`:
    // same_thread is the sequential path (the same bytes, no overlap).
    // `surface`: render.style = surface's, shared with the surface export.
    RenderSink(std::unique_ptr<GlContext> context, const RenderSettings& settings,
               std::filesystem::path png_folder, std::filesystem::path mp4_path, double fps,
               const Mp4Options& mp4_options, EncodeThread encode = EncodeThread::worker,
               std::shared_ptr<FrameSurface> surface = nullptr);
    void write(const Snapshot& frame) override;
    // Waits for the PNGs and finalises the video, also after an early stop.
    void finish() override;
    // Pressure only when the particles are coloured by it.
    FrameFields fields() const override {
        return {.pressure = renderer_.settings().field == ColourField::pressure};
    }

    const GlInfo& gl_info() const { return context_->info(); }
    // Over MPI ranks: the frames composited by depth (FrameRenderer).
    void share_over_ranks(RankCompositing* ranks) { renderer_.share_over_ranks(ranks); }
    std::size_t frames_composited() const { return frames_composited_; }
    // Per frame written; the encoder's part is complete after finish().
    std::vector<FrameCost> costs() const;
    // The encoder's times, totals included (none without a video).
    std::optional<Mp4WriterThread::Times> encode_times() const;
    bool encodes_on_worker() const { return mp4_ && mp4_->on_worker(); }
    // What the frames showed that the user should know (run.json
    // "warnings"), in the order they arose; each arises once a run.
    const std::vector<std::string>& warnings() const { return warnings_; }
    // Each written frame's camera, in order (run.json "camera", camera.csv).
    struct FramePose {
        std::uint64_t frame = 0;
        double time = 0; // s, the snapshot's
        CameraPose pose;
    };
    const std::vector<FramePose>& poses() const { return poses_; }
    int dimension() const { return renderer_.settings().dimension; }
    double scene_aspect() const { return renderer_.scene_aspect(); }
    const std::string& camera_fit() const { return choice_name(renderer_.settings().camera_fit); }

  private:
    void check_range(const Snapshot& frame);

    std::unique_ptr<GlContext> context_;
    FrameRenderer renderer_;
    std::filesystem::path png_folder_;
    std::unique_ptr<PngWriterThread> png_;
    std::unique_ptr<Mp4WriterThread> mp4_;
    std::vector<FrameCost> costs_;
    std::vector<std::string> warnings_;
    std::vector<FramePose> poses_;
    bool range_warned_ = false;
    std::size_t frames_composited_ = 0;
};

} // namespace sph
