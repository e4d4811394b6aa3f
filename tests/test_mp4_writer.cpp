// src/output/mp4_writer: clips written to a temporary folder and decoded back
// with libavformat/libavcodec, as a player would.

#include "output/libav_handles.hpp"
#include "output/mp4_writer.hpp"
#include "support/file_size_cap.hpp"
#include "support/temp_folder.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <sys/resource.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::Image;
using sph::Mp4Options;
using sph::Mp4Writer;
using sph::test::FileSizeCap;
using sph::test::TempFolder;

// Makes `folder` the current folder until it goes out of scope.
class WorkingFolder {
  public:
    explicit WorkingFolder(const fs::path& folder) : previous_(fs::current_path()) {
        fs::current_path(folder);
    }
    ~WorkingFolder() {
        std::error_code ec;
        fs::current_path(previous_, ec);
    }
    WorkingFolder(const WorkingFolder&) = delete;
    WorkingFolder& operator=(const WorkingFolder&) = delete;

  private:
    fs::path previous_;
};

struct Rgb {
    double r, g, b;
};

std::ostream& operator<<(std::ostream& out, Rgb c) {
    return out << fmt::format("({:.1f}, {:.1f}, {:.1f})", c.r, c.g, c.b);
}

// Every channel within `tolerance` (0-255) of the expected colour. Flat
// colours come back within 3 at CRF 20; decoding with the BT.601 matrix
// instead of the tagged BT.709 is off by 20 or more, which 10 catches.
class CloseToColour : public Catch::MatcherBase<Rgb> {
  public:
    explicit CloseToColour(Rgb expected, double tolerance = 10)
        : expected_(expected), tolerance_(tolerance) {}
    bool match(const Rgb& actual) const override {
        return std::abs(actual.r - expected_.r) <= tolerance_ &&
               std::abs(actual.g - expected_.g) <= tolerance_ &&
               std::abs(actual.b - expected_.b) <= tolerance_;
    }
    std::string describe() const override {
        return fmt::format("is within {} of ({}, {}, {})", tolerance_, expected_.r, expected_.g,
                           expected_.b);
    }

  private:
    Rgb expected_;
    double tolerance_;
};

Rgb mean_colour(const Image& image, int x0, int y0, int width, int height) {
    Rgb sum{0, 0, 0};
    for (int y = y0; y < y0 + height; ++y)
        for (int x = x0; x < x0 + width; ++x) {
            const std::uint8_t* p = image.pixel(x, y);
            sum.r += p[0];
            sum.g += p[1];
            sum.b += p[2];
        }
    const double n = double(width) * height;
    return {sum.r / n, sum.g / n, sum.b / n};
}

void fill(Image& image, int x0, int y0, int width, int height, Rgb colour) {
    for (int y = y0; y < y0 + height; ++y)
        for (int x = x0; x < x0 + width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t(colour.r);
            p[1] = std::uint8_t(colour.g);
            p[2] = std::uint8_t(colour.b);
            p[3] = 255;
        }
}

const Rgb background{20, 40, 90};
const Rgb square_colour{230, 30, 30};
constexpr int square_size = 16;

// The square's top-left corner in frame `index` of a clip at least 64x48:
// it moves right and down, wrapping round to stay inside.
int square_x(int index) {
    return (4 + 3 * index) % (64 - square_size);
}
int square_y(int index) {
    return (8 + index) % (48 - square_size);
}

Image moving_square_frame(int width, int height, int index) {
    Image frame(width, height);
    fill(frame, 0, 0, width, height, background);
    fill(frame, square_x(index), square_y(index), square_size, square_size, square_colour);
    return frame;
}

void write_moving_square(const fs::path& path, int width, int height, double fps, int frames) {
    Mp4Writer writer(path, width, height, fps);
    for (int i = 0; i < frames; ++i)
        writer.write(moving_square_frame(width, height, i));
    writer.finish();
    REQUIRE(writer.frames_written() == std::uint64_t(frames));
}

// What a player finds in the file.
struct DecodedVideo {
    std::string codec;
    std::string pixel_format;
    AVColorSpace colour_space = AVCOL_SPC_UNSPECIFIED;
    int width = 0;
    int height = 0;
    double duration_s = 0; // the stream's, else the container's
    double frame_rate = 0; // the stream's average
    std::vector<Image> frames;
};

struct InputDeleter {
    void operator()(AVFormatContext* context) const { avformat_close_input(&context); }
};
using sph::libav::CodecContextDeleter;
using sph::libav::FrameDeleter;
using sph::libav::PacketDeleter;
using sph::libav::ScalerDeleter;

// Back to RGBA with the matrix and range the frame is tagged with.
Image to_rgba(const AVFrame& frame) {
    std::unique_ptr<SwsContext, ScalerDeleter> scaler(sws_getContext(
        frame.width, frame.height, AVPixelFormat(frame.format), frame.width, frame.height,
        AV_PIX_FMT_RGBA, SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr));
    REQUIRE(scaler);
    const int* matrix = sws_getCoefficients(frame.colorspace);
    sws_setColorspaceDetails(scaler.get(), matrix, frame.color_range == AVCOL_RANGE_JPEG, matrix, 1,
                             0, 1 << 16, 1 << 16);
    Image image(frame.width, frame.height);
    std::uint8_t* rgba = image.rgba.data();
    const int stride = image.width * 4;
    sws_scale(scaler.get(), frame.data, frame.linesize, 0, frame.height, &rgba, &stride);
    return image;
}

DecodedVideo decode(const fs::path& path) {
    AVFormatContext* opened = nullptr;
    REQUIRE(avformat_open_input(&opened, path.c_str(), nullptr, nullptr) == 0);
    std::unique_ptr<AVFormatContext, InputDeleter> input(opened);
    REQUIRE(avformat_find_stream_info(input.get(), nullptr) >= 0);
    const int stream_index =
        av_find_best_stream(input.get(), AVMEDIA_TYPE_VIDEO, -1, -1, nullptr, 0);
    REQUIRE(stream_index >= 0);
    const AVStream& stream = *input->streams[stream_index];

    const AVCodec* decoder = avcodec_find_decoder(stream.codecpar->codec_id);
    REQUIRE(decoder);
    std::unique_ptr<AVCodecContext, CodecContextDeleter> codec(avcodec_alloc_context3(decoder));
    REQUIRE(avcodec_parameters_to_context(codec.get(), stream.codecpar) >= 0);
    REQUIRE(avcodec_open2(codec.get(), decoder, nullptr) == 0);

    DecodedVideo video;
    video.codec = decoder->name;
    const char* format_name = av_get_pix_fmt_name(AVPixelFormat(stream.codecpar->format));
    video.pixel_format = format_name ? format_name : "none";
    video.colour_space = stream.codecpar->color_space;
    video.width = stream.codecpar->width;
    video.height = stream.codecpar->height;
    video.duration_s = stream.duration != AV_NOPTS_VALUE
                           ? double(stream.duration) * av_q2d(stream.time_base)
                           : double(input->duration) / AV_TIME_BASE;
    video.frame_rate = av_q2d(stream.avg_frame_rate);

    std::unique_ptr<AVPacket, PacketDeleter> packet(av_packet_alloc());
    std::unique_ptr<AVFrame, FrameDeleter> frame(av_frame_alloc());
    auto receive_frames = [&] {
        while (avcodec_receive_frame(codec.get(), frame.get()) == 0)
            video.frames.push_back(to_rgba(*frame));
    };
    while (av_read_frame(input.get(), packet.get()) >= 0) {
        if (packet->stream_index == stream_index)
            REQUIRE(avcodec_send_packet(codec.get(), packet.get()) >= 0);
        av_packet_unref(packet.get());
        receive_frames();
    }
    REQUIRE(avcodec_send_packet(codec.get(), nullptr) >= 0);
    receive_frames();
    return video;
}

// Top-level MP4 box types in file order ("ftyp", "moov", "mdat", ...).
std::vector<std::string> top_level_boxes(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(file), {}};
    auto be = [&](std::size_t at, int count) {
        std::uint64_t value = 0;
        for (int i = 0; i < count; ++i)
            value = value << 8 | std::uint8_t(bytes[at + i]);
        return value;
    };
    std::vector<std::string> boxes;
    std::size_t at = 0;
    while (at + 8 <= bytes.size()) {
        std::uint64_t size = be(at, 4);
        boxes.push_back(bytes.substr(at + 4, 4));
        if (size == 1 && at + 16 <= bytes.size())
            size = be(at + 8, 8);
        else if (size == 0)
            size = bytes.size() - at;
        if (size < 8)
            break;
        at += size;
    }
    return boxes;
}

std::size_t position(const std::vector<std::string>& names, const std::string& name) {
    return std::size_t(std::find(names.begin(), names.end(), name) - names.begin());
}

} // namespace

// FFmpeg is loaded when the first video is written, not linked: every
// function the writer calls must be in the libraries of the headers built
// against (a missing one would fail a user's first clip, not the build).
TEST_CASE("FFmpeg's functions load from its libraries on first use", "[mp4]") {
    const sph::libav::Functions* functions = nullptr;
    REQUIRE_NOTHROW(functions = &sph::libav::functions());
    CHECK(functions->avcodec_send_frame != nullptr);
    CHECK(functions->sws_scale != nullptr);
    CHECK(&sph::libav::functions() == functions);
}

TEST_CASE("a clip decodes to the frames, size, format and duration written", "[mp4]") {
    if (!Mp4Writer::available()) {
        WARN("this libavcodec has no libx264; MP4 tests skipped");
        return;
    }
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    write_moving_square(path, 64, 48, 30, 12);

    REQUIRE(fs::exists(path));
    CHECK(folder.entries() == std::vector<std::string>{"clip.mp4"});
    const DecodedVideo video = decode(path);
    CHECK(video.codec == "h264");
    CHECK(video.pixel_format == "yuv420p");
    CHECK(video.colour_space == AVCOL_SPC_BT709);
    CHECK(video.width == 64);
    CHECK(video.height == 48);
    CHECK(video.frames.size() == 12);
    CHECK(video.duration_s == Approx(12.0 / 30).margin(1.0 / 30));
    CHECK(video.frame_rate == Approx(30));

    // Faststart: a player reads the index before the frames.
    const std::vector<std::string> boxes = top_level_boxes(path);
    INFO("boxes: " << fmt::format("{}", fmt::join(boxes, " ")));
    CHECK(position(boxes, "moov") < position(boxes, "mdat"));
    CHECK(position(boxes, "mdat") < boxes.size());
}

TEST_CASE("a colon in a relative file name is part of the name, not a protocol", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    // libavformat would read "crf:20.mp4" as protocol "crf", path "20.mp4".
    {
        const WorkingFolder inside(folder / ".");
        write_moving_square("crf:20.mp4", 64, 48, 30, 2);
    }
    CHECK(folder.entries() == std::vector<std::string>{"crf:20.mp4"});
    CHECK(decode(folder / "crf:20.mp4").frames.size() == 2);
}

TEST_CASE("decoded colours are close to the written ones, frames in order", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    write_moving_square(path, 64, 48, 30, 12);
    const DecodedVideo video = decode(path);
    REQUIRE(video.frames.size() == 12);

    // Inside the square, 2 pixels in from its edges where chroma is shared
    // with the background.
    const int inner = square_size - 4;
    const Image& first = video.frames.front();
    const Image& last = video.frames.back();
    CHECK_THAT(mean_colour(first, square_x(0) + 2, square_y(0) + 2, inner, inner),
               CloseToColour(square_colour));
    CHECK_THAT(mean_colour(last, square_x(11) + 2, square_y(11) + 2, inner, inner),
               CloseToColour(square_colour));
    // The square has moved on from where it started.
    CHECK_THAT(mean_colour(last, square_x(0) + 2, square_y(0) + 2, inner, inner),
               CloseToColour(background));
    CHECK_THAT(mean_colour(first, 56, 0, 8, 48), CloseToColour(background));
}

TEST_CASE("an odd size is encoded at the next even size, the last row and column repeated",
          "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "odd.mp4";
    const Rgb blue{30, 60, 200}, green{40, 200, 60}, red{220, 40, 40};
    // Green on the right and red along the bottom, so that the repeated
    // column and row are green and red: black padding would fail.
    Image frame(65, 47);
    fill(frame, 0, 0, 65, 47, blue);
    fill(frame, 57, 0, 8, 40, green);
    fill(frame, 0, 40, 65, 7, red);
    {
        Mp4Writer writer(path, 65, 47, 30);
        for (int i = 0; i < 3; ++i)
            writer.write(frame);
        writer.finish();
    }
    const DecodedVideo video = decode(path);
    CHECK(video.width == 66);
    CHECK(video.height == 48);
    REQUIRE(video.frames.size() == 3);
    const Image& decoded = video.frames.front();
    CHECK_THAT(mean_colour(decoded, 65, 2, 1, 34), CloseToColour(green));
    CHECK_THAT(mean_colour(decoded, 2, 47, 50, 1), CloseToColour(red));
    CHECK_THAT(mean_colour(decoded, 2, 2, 50, 34), CloseToColour(blue));
}

TEST_CASE("the duration is frames / fps for 24 and 29.97 fps", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    const double fps = GENERATE(24.0, 29.97);
    const int frames = GENERATE(1, 30);
    TempFolder folder;
    const fs::path path = folder / "rate.mp4";
    write_moving_square(path, 64, 48, fps, frames);
    const DecodedVideo video = decode(path);
    INFO(fps << " fps, " << frames << " frames");
    CHECK(video.frames.size() == std::size_t(frames));
    CHECK(video.duration_s == Approx(frames / fps).margin(0.5 / fps));
    CHECK(video.frame_rate == Approx(fps));
}

TEST_CASE("bad arguments and unwritable paths are refused", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";

    SECTION("a frame of the wrong size") {
        Mp4Writer writer(path, 64, 48, 30);
        CHECK_THROWS_AS(writer.write(Image(48, 64)), std::invalid_argument);
        CHECK_THROWS_AS(writer.write(Image(64, 46)), std::invalid_argument);
        // Refused before encoding: the writer carries on.
        writer.write(moving_square_frame(64, 48, 0));
        writer.finish();
        CHECK(decode(path).frames.size() == 1);
    }
    SECTION("a folder that cannot exist") {
        const fs::path unwritable = "/proc/x/y.mp4";
        CHECK_THROWS_AS(Mp4Writer(unwritable, 64, 48, 30), std::runtime_error);
        CHECK_THROWS_WITH(Mp4Writer(unwritable, 64, 48, 30), Catch::Contains("/proc/x/y.mp4"));
    }
    SECTION("settings out of range") {
        CHECK_THROWS_AS(Mp4Writer(path, 0, 48, 30), std::invalid_argument);
        CHECK_THROWS_AS(Mp4Writer(path, 64, 48, 0), std::invalid_argument);
        CHECK_THROWS_AS(Mp4Writer(path, 64, 48, std::nan("")), std::invalid_argument);
        CHECK_THROWS_AS(Mp4Writer(path, 64, 48, 30, Mp4Options{.crf = 52}), std::invalid_argument);
        CHECK_THROWS_WITH(Mp4Writer(path, 64, 48, 30, Mp4Options{.preset = "warp"}),
                          Catch::Contains("warp") && Catch::Contains(path.string()));
        CHECK(folder.entries().empty());
    }
}

TEST_CASE("a writer destroyed without finish() leaves a complete video", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    {
        Mp4Writer writer(path, 64, 48, 30);
        for (int i = 0; i < 5; ++i)
            writer.write(moving_square_frame(64, 48, i));
    }
    CHECK(folder.entries() == std::vector<std::string>{"clip.mp4"});
    const DecodedVideo video = decode(path);
    CHECK(video.frames.size() == 5);
    CHECK(video.duration_s == Approx(5.0 / 30).margin(1.0 / 30));
}

TEST_CASE("no frames, no file", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    {
        Mp4Writer writer(path, 64, 48, 30);
        CHECK(fs::exists(path.string() + ".partial"));
        writer.finish();
        CHECK(writer.frames_written() == 0);
    }
    { Mp4Writer destroyed_unfinished(folder / "other.mp4", 64, 48, 30); }
    CHECK(folder.entries().empty());
}

TEST_CASE("a video that cannot be written completely leaves no file", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    // Noise does not compress: 20 frames of it are far more than 64 KiB.
    std::mt19937 random(1);
    Image noise(256, 256);
    bool refused = false;
    {
        FileSizeCap cap(64 * 1024);
        Mp4Writer writer(path, 256, 256, 30);
        try {
            for (int i = 0; i < 20; ++i) {
                for (std::uint8_t& byte : noise.rgba)
                    byte = std::uint8_t(random());
                writer.write(noise);
            }
            writer.finish();
        } catch (const std::runtime_error& e) {
            refused = true;
            CHECK_THAT(e.what(), Catch::Contains(path.string()));
            writer.finish();
        }
    }
    CHECK(refused);
    CHECK(folder.entries().empty());
}

TEST_CASE("an existing file is replaced only by finish(), once", "[mp4]") {
    if (!Mp4Writer::available())
        return;
    TempFolder folder;
    const fs::path path = folder / "clip.mp4";
    std::ofstream(path) << "an older video";
    Mp4Writer writer(path, 64, 48, 30);
    for (int i = 0; i < 3; ++i)
        writer.write(moving_square_frame(64, 48, i));
    CHECK(fs::file_size(path) == std::string("an older video").size());

    writer.finish();
    writer.finish();
    CHECK(folder.entries() == std::vector<std::string>{"clip.mp4"});
    CHECK(decode(path).frames.size() == 3);
    CHECK_THROWS_AS(writer.write(moving_square_frame(64, 48, 3)), std::logic_error);
}
