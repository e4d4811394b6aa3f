#include "output/mp4_writer_thread.hpp"

#include "sph/wall_clock.hpp"

#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace sph {
Mp4WriterThread::Mp4WriterThread(const std::filesystem::path& path, int width, int height,
                                 double fps, const Mp4Options& options, std::size_t capacity,
                                 EncodeThread thread)
    : capacity_(capacity > 0 ? capacity : 1), thread_(thread),
      writer_(path, width, height, fps, options) {
    if (thread_ == EncodeThread::worker)
        worker_ = std::thread([this] { work(); });
}

Mp4WriterThread::~Mp4WriterThread() {
    try {
        finish();
    } catch (const std::exception& e) {
        // fprintf, not fmt::print: a destructor must not throw.
        std::fprintf(stderr, "sphclip: error: %s\n", e.what());
    }
}

void Mp4WriterThread::submit(std::shared_ptr<const Image> frame) {
    if (!frame)
        throw std::invalid_argument("Mp4WriterThread::submit without a frame");
    if (thread_ == EncodeThread::same_thread) {
        {
            std::lock_guard lock(mutex_);
            if (finished_)
                throw std::logic_error("Mp4WriterThread::submit after finish");
            if (error_)
                std::rethrow_exception(error_);
            times_.frame_wait_seconds.push_back(0);
        }
        encode(*frame);
        std::lock_guard lock(mutex_);
        if (error_)
            std::rethrow_exception(error_);
        return;
    }
    const auto start = Clock::now();
    std::unique_lock lock(mutex_);
    if (finished_)
        throw std::logic_error("Mp4WriterThread::submit after finish");
    taken_.wait(lock, [&] { return queue_.size() < capacity_ || error_; });
    if (error_)
        std::rethrow_exception(error_);
    queue_.push_back(std::move(frame));
    times_.frame_wait_seconds.push_back(seconds_since(start));
    queued_.notify_one();
}

void Mp4WriterThread::finish() {
    {
        std::lock_guard lock(mutex_);
        if (finished_)
            return;
        finished_ = true;
        closing_ = true;
    }
    if (thread_ == EncodeThread::worker) {
        const auto start = Clock::now();
        queued_.notify_one();
        worker_.join();
        std::lock_guard lock(mutex_);
        times_.finish_wait_seconds = seconds_since(start);
    } else {
        flush();
    }
    // The worker has stopped: error_ is no longer written.
    if (error_)
        std::rethrow_exception(error_);
}

Mp4WriterThread::Times Mp4WriterThread::times() const {
    std::lock_guard lock(mutex_);
    return times_;
}

void Mp4WriterThread::work() {
    for (;;) {
        std::shared_ptr<const Image> frame;
        bool failed = false;
        {
            std::unique_lock lock(mutex_);
            queued_.wait(lock, [&] { return !queue_.empty() || closing_; });
            if (queue_.empty())
                break;
            frame = std::move(queue_.front());
            queue_.pop_front();
            failed = bool(error_);
        }
        taken_.notify_all();
        // After a failure the rest is dropped: the video is discarded anyway.
        if (!failed)
            encode(*frame);
    }
    // The flush runs here too, so that finish() only waits.
    flush();
}

void Mp4WriterThread::encode(const Image& frame) {
    // Encoding happens unlocked, so that submit() can queue the next frame meanwhile.
    const auto start = Clock::now();
    try {
        writer_.write(frame);
    } catch (...) {
        std::lock_guard lock(mutex_);
        error_ = std::current_exception();
        taken_.notify_all();
        return;
    }
    std::lock_guard lock(mutex_);
    times_.frame_seconds.push_back(seconds_since(start));
}

void Mp4WriterThread::flush() {
    const auto start = Clock::now();
    // After a failed write, Mp4Writer::finish() removes the partial file and
    // throws nothing; the write's error is the one reported.
    try {
        writer_.finish();
    } catch (...) {
        std::lock_guard lock(mutex_);
        if (!error_)
            error_ = std::current_exception();
    }
    std::lock_guard lock(mutex_);
    times_.flush_seconds = seconds_since(start);
}

} // namespace sph
