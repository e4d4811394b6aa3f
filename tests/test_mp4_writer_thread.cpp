// src/output/mp4_writer_thread: the encoder on its own thread writes the same
// bytes as the sequential path (STYLE.md point 13), reports failures on the
// caller's thread, and times itself.

#include "output/mp4_writer_thread.hpp"
#include "support/file_size_cap.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <sys/resource.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::EncodeThread;
using sph::Image;
using sph::Mp4Options;
using sph::Mp4Writer;
using sph::Mp4WriterThread;
using sph::test::FileSizeCap;
using sph::test::TempFolder;

// A gradient with a moving disc and a noisy band: motion and texture, so
// that libx264 makes real decisions (and its threads have work to split).
std::shared_ptr<const Image> test_frame(int width, int height, int index) {
    auto frame = std::make_shared<Image>(width, height);
    std::mt19937 random{std::uint32_t(index)};
    const int cx = 20 + 5 * index, cy = height / 2;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = frame->pixel(x, y);
            const bool disc = (x - cx) * (x - cx) + (y - cy) * (y - cy) < 400;
            const bool band = y > height - 24;
            p[0] = disc ? 240 : std::uint8_t(x * 255 / width);
            p[1] = band ? std::uint8_t(random()) : std::uint8_t(y * 255 / height);
            p[2] = disc ? 40 : 128;
            p[3] = 255;
        }
    return frame;
}

std::string bytes_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

constexpr int width = 192, height = 108, frames = 24;

void encode_directly(const fs::path& path, const Mp4Options& options) {
    Mp4Writer writer(path, width, height, 30, options);
    for (int i = 0; i < frames; ++i)
        writer.write(*test_frame(width, height, i));
    writer.finish();
}

void encode_with(EncodeThread thread, const fs::path& path, const Mp4Options& options) {
    Mp4WriterThread writer(path, width, height, 30, options, 2, thread);
    for (int i = 0; i < frames; ++i)
        writer.submit(test_frame(width, height, i));
    writer.finish();
}

} // namespace

TEST_CASE("the encoder thread writes the same bytes as the sequential path", "[mp4][pipeline]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    // threads 0: libx264's own frame threads (the run's default), 1: none.
    for (const Mp4Options& options : {Mp4Options{20, "veryfast", 0}, Mp4Options{20, "ultrafast", 1},
                                      Mp4Options{20, "faster", 1}, Mp4Options{20, "medium", 2}}) {
        INFO("preset " << options.preset << ", threads " << options.threads);
        encode_directly(folder / "direct.mp4", options);
        encode_with(EncodeThread::same_thread, folder / "same_thread.mp4", options);
        encode_with(EncodeThread::worker, folder / "worker.mp4", options);
        encode_with(EncodeThread::worker, folder / "worker_again.mp4", options);
        encode_directly(folder / "direct_again.mp4", options);
        const std::string direct = bytes_of(folder / "direct.mp4");
        REQUIRE(direct.size() > 1000);
        CHECK((bytes_of(folder / "same_thread.mp4") == direct));
        CHECK((bytes_of(folder / "worker.mp4") == direct));
        // The same bytes from encoder to encoder, threads or not: with the
        // macroblock tree on, libx264 0.164 fails this at this size.
        CHECK((bytes_of(folder / "worker_again.mp4") == direct));
        CHECK((bytes_of(folder / "direct_again.mp4") == direct));
    }
}

TEST_CASE("the encoder thread times every frame and the caller's waits", "[mp4][pipeline]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    for (EncodeThread thread : {EncodeThread::worker, EncodeThread::same_thread}) {
        Mp4WriterThread writer(folder / "clip.mp4", width, height, 30, {}, 2, thread);
        for (int i = 0; i < frames; ++i)
            writer.submit(test_frame(width, height, i));
        writer.finish();
        const auto times = writer.times();
        REQUIRE(times.frame_seconds.size() == std::size_t(frames));
        REQUIRE(times.frame_wait_seconds.size() == std::size_t(frames));
        for (int i = 0; i < frames; ++i) {
            CHECK(times.frame_seconds[i] > 0);
            CHECK(times.frame_wait_seconds[i] >= 0);
        }
        CHECK(times.flush_seconds > 0);
        if (thread == EncodeThread::same_thread) {
            CHECK(times.finish_wait_seconds == 0);
            CHECK(times.frame_wait_seconds.back() == 0);
        }
        CHECK(fs::file_size(folder / "clip.mp4") > 1000);
    }
}

TEST_CASE("an encoder failure surfaces on the caller's thread and leaves no file",
          "[mp4][pipeline]") {
    if (!Mp4Writer::available())
        return;
    for (EncodeThread thread : {EncodeThread::worker, EncodeThread::same_thread}) {
        TempFolder folder;
        const fs::path path = folder / "clip.mp4";
        // Noise does not compress: 40 frames of it are far more than 64 KiB.
        std::mt19937 random(1);
        bool refused = false;
        {
            FileSizeCap cap(64 * 1024);
            Mp4WriterThread writer(path, 256, 256, 30, {}, 2, thread);
            try {
                for (int i = 0; i < 40; ++i) {
                    auto noise = std::make_shared<Image>(256, 256);
                    for (std::uint8_t& byte : noise->rgba)
                        byte = std::uint8_t(random());
                    writer.submit(std::move(noise));
                }
                writer.finish();
            } catch (const std::runtime_error& e) {
                refused = true;
                // Mp4Writer's own message, as on the sequential path.
                CHECK_THAT(e.what(), Catch::Contains("cannot write video " + path.string()));
            }
            // finish() reports the error once more if submit() saw it first;
            // after that it does nothing.
            try {
                writer.finish();
            } catch (const std::runtime_error&) {
            }
            CHECK_NOTHROW(writer.finish());
        }
        CHECK(refused);
        CHECK(folder.entries().empty());
    }
}

TEST_CASE("the encoder thread finishes its video when destroyed, and refuses late frames",
          "[mp4][pipeline]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    {
        Mp4WriterThread writer(folder / "clip.mp4", width, height, 30);
        for (int i = 0; i < 5; ++i)
            writer.submit(test_frame(width, height, i));
    }
    CHECK(folder.entries() == std::vector<std::string>{"clip.mp4"});
    CHECK(fs::file_size(folder / "clip.mp4") > 1000);

    Mp4WriterThread writer(folder / "other.mp4", width, height, 30);
    writer.submit(test_frame(width, height, 0));
    writer.finish();
    CHECK_THROWS_AS(writer.submit(test_frame(width, height, 1)), std::logic_error);
    // A bad setting throws on the caller's thread, from the constructor.
    CHECK_THROWS_AS(Mp4WriterThread(folder / "bad.mp4", width, height, 30, {60, "veryfast", 0}),
                    std::invalid_argument);
}
