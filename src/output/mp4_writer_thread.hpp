#pragma once
// The MP4 encoder (colour conversion, libx264, muxing) on a thread of its
// own, so that while frame k is encoded, frame k+1 is simulated and rendered.
//
// The encoder sees the same frames in the same order as an Mp4Writer called
// directly, so the file is the same, byte for byte (the `same_thread` mode
// exists so that tests can compare the two). libx264 is deterministic for a
// given preset and thread count; a different thread count gives a different
// (equally valid) stream.
//
// At most `capacity` frames wait: submit() blocks while the queue is full,
// which bounds the memory held (a 1920x1080 frame is 8 MiB). The first failure
// stops the encoder: frames queued after it are dropped, the partial file is
// removed (as Mp4Writer does), and the error is rethrown by the next submit()
// and by finish().

#include "output/image.hpp"
#include "output/mp4_writer.hpp"

#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace sph {

enum class EncodeThread {
    worker,      // a thread of its own (the run's default)
    same_thread, // the caller's thread, inside submit() and finish(): the sequential path
};

class Mp4WriterThread {
  public:
    // Opens the video on the caller's thread, so that a bad path or setting
    // throws here, as Mp4Writer's constructor does.
    Mp4WriterThread(const std::filesystem::path& path, int width, int height, double fps,
                    const Mp4Options& options = {}, std::size_t capacity = 2,
                    EncodeThread thread = EncodeThread::worker);
    // Calls finish(); an error it would throw goes to stderr, so call
    // finish() first to see it.
    ~Mp4WriterThread();
    Mp4WriterThread(const Mp4WriterThread&) = delete;
    Mp4WriterThread& operator=(const Mp4WriterThread&) = delete;

    // Queues a frame (width x height). The image is shared, not copied: the
    // PNG writer may hold the same one.
    void submit(std::shared_ptr<const Image> frame);
    // Encodes what is queued, flushes the encoder and finalises the file.
    // Idempotent; throws the first error (Mp4Writer's messages).
    void finish();

    struct Times {
        // Per frame submitted, in order: seconds the encoder took for it (on
        // whichever thread encodes). Frames dropped after a failure have none.
        std::vector<double> frame_seconds;
        double flush_seconds = 0; // finish(): the frames libx264 held back, the index
        // Seconds the caller spent blocked in submit() (full queue) and in
        // finish() (waiting for the worker). Zero in `same_thread` mode,
        // where the encoding itself is the caller's time.
        std::vector<double> frame_wait_seconds;
        double finish_wait_seconds = 0;
    };
    Times times() const;
    bool on_worker() const { return thread_ == EncodeThread::worker; }

  private:
    void work();
    void encode(const Image& frame);
    void flush();

    const std::size_t capacity_;
    const EncodeThread thread_;
    Mp4Writer writer_;
    mutable std::mutex mutex_;
    std::condition_variable queued_; // a frame arrived, or finish() was called
    std::condition_variable taken_;  // a frame left the queue, or encoding failed
    std::deque<std::shared_ptr<const Image>> queue_;
    bool closing_ = false;
    bool finished_ = false;
    std::exception_ptr error_;
    Times times_;
    std::thread worker_; // last: started once everything above exists
};

} // namespace sph
