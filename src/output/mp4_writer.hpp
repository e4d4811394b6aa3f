#pragma once
// H.264 video written in-process with libavcodec/libavformat: frames go
// straight from memory to libx264, no ffmpeg program and no temporary images.
//
// The file is written as `path` + ".partial" and renamed to `path` by
// finish(), so a player never sees a truncated file; the index (moov atom)
// is at the front ("faststart") so a browser can start playing before the
// whole file has arrived.
//
// Pixels: yuv420p, BT.709 matrix, limited range, tagged as such (sRGB shares
// BT.709's primaries, and players expect the BT.709 tags on sRGB content).
//
// Odd sizes: yuv420p needs an even width and height, so a W x H image is
// encoded as ceil-to-even(W) x ceil-to-even(H), the extra column or row a
// copy of the last one. A 65x47 image decodes as 66x48.
//
// No frames, no file: finish() after zero frames removes the temporary file
// and creates nothing. A failed write() also leaves nothing behind: finish()
// then discards the partial file rather than rename a broken video into place.

#include "output/image.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

namespace sph {

struct Mp4Options {
    int crf = 20;                    // constant quality (x264 CRF), 0-51, lower is better
    std::string preset = "veryfast"; // x264 preset, "ultrafast" to "placebo"
    int threads = 0;                 // encoder threads, 0 = libx264's choice
    // libx264's macroblock tree (part of its rate control). Off by default:
    // Debian's libx264 0.164 then reads uninitialised memory on some inputs
    // (small frames, e.g. 320x180), so the same frames could encode to
    // different bytes from one encoder to the next in one process; off, the
    // bytes depend only on the frames and these settings (docs/rendering.md, "What
    // encoding costs", gives the price).
    bool mb_tree = false;
};

class Mp4Writer {
  public:
    // Throws std::invalid_argument for a size below 1, a non-finite or
    // non-positive fps, or a CRF outside 0-51; std::runtime_error naming the
    // path when libx264 is missing or the file cannot be opened.
    Mp4Writer(const std::filesystem::path& path, int width, int height, double fps,
              const Mp4Options& options = {});
    // Finishes the file if finish() was not called; never throws (a failure
    // is reported on stderr).
    ~Mp4Writer();
    Mp4Writer(const Mp4Writer&) = delete;
    Mp4Writer& operator=(const Mp4Writer&) = delete;

    // The frame must be width x height (std::invalid_argument otherwise).
    // Throws std::logic_error after finish(), std::runtime_error when
    // encoding or writing fails.
    void write(const Image& frame);
    // Flushes the encoder, writes the index, closes and renames the file.
    // Idempotent. Throws std::runtime_error naming the path on failure, and
    // then leaves no file.
    void finish();

    std::uint64_t frames_written() const { return frames_written_; }
    // Whether this libavcodec has the libx264 encoder.
    static bool available();
    // Why no MP4 can be written here (FFmpeg's libraries cannot be loaded,
    // or libavcodec has no libx264), or "" when one can: loads FFmpeg.
    static std::string unavailable_reason();

  private:
    // libav state lives in the .cpp so that users of this header need no
    // libav headers.
    struct Encoder;

    std::filesystem::path path_;
    int width_;
    int height_;
    std::unique_ptr<Encoder> encoder_; // null once finished
    std::uint64_t frames_written_ = 0;
    bool failed_ = false; // a write failed: finish() discards the file
};

} // namespace sph
