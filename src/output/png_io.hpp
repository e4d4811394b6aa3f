#pragma once
// PNG files: frames written by the renderer, images read back by `compare`.

#include "output/image.hpp"

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>

namespace sph {

// Writes `image` as an 8-bit PNG: RGB when every alpha is 255 (rendered frames
// are opaque, and a quarter less data compresses faster), RGBA otherwise.
// The file appears whole or not at all (write_file_atomically). Throws
// std::runtime_error naming the path; std::invalid_argument for an empty image
// or one whose pixel buffer does not match its size.
void write_png(const std::filesystem::path& path, const Image& image);

// A PNG that cannot be opened or decoded.
struct ImageReadError : std::runtime_error {
    std::filesystem::path path;
    std::string reason;
    ImageReadError(std::filesystem::path path_, std::string reason_)
        : std::runtime_error("cannot read the PNG " + path_.string() + ": " + reason_),
          path(std::move(path_)), reason(std::move(reason_)) {}
};

// The largest PNG read: a side of 16384 pixels (the largest render.size),
// and 64 Mi pixels (256 MiB as RGBA) in all. Checked from the header before
// decoding; the file itself is at most png_file_limit (output/files.hpp).
inline constexpr int max_png_side = 16384;
inline constexpr long long max_png_pixels = 64LL << 20;

// Reads any PNG (grey, palette, 16-bit: converted) as 8-bit RGBA; alpha is
// 255 where the file has none. Decoded by libpng (Debian libpng-dev), which
// checks every chunk's CRC; no gamma conversion. Only a regular file within
// png_file_limit is read. Throws ImageReadError.
Image read_png(const std::filesystem::path& path);
// The same from the file's bytes; `path` names it in errors.
Image decode_png(std::string_view bytes, const std::filesystem::path& path);

// Writes PNGs on a thread of its own, in the order submitted, so that encoding
// overlaps the next frame's simulation and rendering. At most `capacity`
// images wait in the queue: submit() blocks while it is full, which bounds
// the memory held. The first failure stops the writer: images queued after it
// are dropped, and the error is rethrown by every later submit() and by
// finish().
class PngWriterThread {
  public:
    explicit PngWriterThread(std::size_t capacity = 3);
    // Calls finish(); an error it would throw is lost, so call finish() first
    // to see it.
    ~PngWriterThread();
    PngWriterThread(const PngWriterThread&) = delete;
    PngWriterThread& operator=(const PngWriterThread&) = delete;

    void submit(std::filesystem::path path, Image image);
    // The image is shared, not copied: the MP4 encoder may hold the same one.
    void submit(std::filesystem::path path, std::shared_ptr<const Image> image);
    // Waits until every submitted image is written and stops the thread.
    // Later calls do nothing.
    void finish();

  private:
    struct Job {
        std::filesystem::path path;
        std::shared_ptr<const Image> image;
    };
    void work();

    const std::size_t capacity_;
    std::mutex mutex_;
    std::condition_variable queued_; // a job arrived, or finish() was called
    std::condition_variable taken_;  // a job left the queue, or a write failed
    std::deque<Job> queue_;
    bool closing_ = false;
    bool finished_ = false;
    std::exception_ptr error_;
    std::thread worker_;
};

} // namespace sph
