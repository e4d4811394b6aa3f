#include "output/mp4_writer.hpp"

#include "output/files.hpp"
#include "output/libav_handles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fmt/format.h>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace sph {
namespace {

const libav::Functions& av() {
    return libav::functions();
}

std::string av_error_text(int error) {
    char text[AV_ERROR_MAX_STRING_SIZE] = {};
    av().av_strerror(error, text, sizeof text);
    return text;
}

// Returns `result`, or throws naming the video and libav's reason; a full
// disk (or `ulimit -f`) as OutOfSpaceError, which a run reports as such.
int check(int result, const std::filesystem::path& path, std::string_view doing) {
    if (result >= 0)
        return result;
    const std::string message =
        fmt::format("cannot write video {}: {}: {}", path.string(), doing, av_error_text(result));
    if (is_out_of_space(AVUNERROR(result)))
        throw OutOfSpaceError(path, AVUNERROR(result), message);
    throw std::runtime_error(message);
}

struct FormatContextDeleter {
    void operator()(AVFormatContext* context) const {
        if (context->pb && !(context->oformat->flags & AVFMT_NOFILE))
            av().avio_closep(&context->pb);
        av().avformat_free_context(context);
    }
};
using libav::CodecContextDeleter;
using libav::FrameDeleter;
using libav::PacketDeleter;
using libav::ScalerDeleter;

// The ".partial" file: removed when this goes out of scope unless kept.
struct TemporaryFile {
    std::filesystem::path path; // empty until the file exists
    ~TemporaryFile() {
        std::error_code ignored;
        if (!path.empty())
            std::filesystem::remove(path, ignored);
    }
};

// libx264 reports its settings and statistics at "info" level on every open
// and close; only problems belong on the program's stderr.
void quiet_libav_logging() {
    static std::once_flag once;
    std::call_once(once, [] { av().av_log_set_level(AV_LOG_ERROR); });
}

int round_up_to_even(int n) {
    return n + (n & 1);
}

// Replicating the last column and row (rather than padding with black) keeps
// the padding the colour of its neighbours: it costs almost no bits, and the
// 2x2 chroma of the last real row and column is not darkened.
void pad_by_replicating_edges(const Image& frame, std::vector<std::uint8_t>& padded,
                              int padded_width, int padded_height) {
    const std::size_t row_bytes = std::size_t(frame.width) * 4;
    const std::size_t padded_row_bytes = std::size_t(padded_width) * 4;
    for (int y = 0; y < padded_height; ++y) {
        const std::uint8_t* source = frame.pixel(0, std::min(y, frame.height - 1));
        std::uint8_t* target = padded.data() + std::size_t(y) * padded_row_bytes;
        std::memcpy(target, source, row_bytes);
        if (padded_width > frame.width)
            std::memcpy(target + row_bytes, source + row_bytes - 4, 4);
    }
}

} // namespace

// Members are destroyed in reverse order: the temporary file is removed only
// after the format context has closed it.
struct Mp4Writer::Encoder {
    TemporaryFile partial;
    std::unique_ptr<AVFormatContext, FormatContextDeleter> format;
    std::unique_ptr<AVCodecContext, CodecContextDeleter> codec;
    AVStream* stream = nullptr; // owned by `format`
    std::unique_ptr<AVFrame, FrameDeleter> yuv;
    std::unique_ptr<AVPacket, PacketDeleter> packet;
    std::unique_ptr<SwsContext, ScalerDeleter> scaler;
    // An odd-sized frame copied to the even encoded size; empty when even.
    std::vector<std::uint8_t> padded_rgba;

    // Sends `frame` (nullptr: end of stream) and writes every packet the
    // encoder has ready.
    void encode(const AVFrame* frame, const std::filesystem::path& path) {
        check(av().avcodec_send_frame(codec.get(), frame), path, "encoding a frame");
        for (;;) {
            const int received = av().avcodec_receive_packet(codec.get(), packet.get());
            if (received == AVERROR(EAGAIN) || received == AVERROR_EOF)
                return;
            check(received, path, "encoding a frame");
            // libx264 leaves the duration unset; each frame lasts one tick of
            // 1/fps, and the last one's sets the length of the video.
            if (packet->duration == 0)
                packet->duration = 1;
            av().av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
            packet->stream_index = stream->index;
            check(av().av_interleaved_write_frame(format.get(), packet.get()), path,
                  "writing a frame");
        }
    }
};

Mp4Writer::Mp4Writer(const std::filesystem::path& path, int width, int height, double fps,
                     const Mp4Options& options)
    : path_(path), width_(width), height_(height) {
    if (width < 1 || height < 1)
        throw std::invalid_argument(
            fmt::format("video {}: size {}x{} is not positive", path.string(), width, height));
    const AVRational frame_rate = av().av_d2q(fps, 100000);
    if (!std::isfinite(fps) || fps <= 0 || frame_rate.num <= 0 || frame_rate.den <= 0)
        throw std::invalid_argument(
            fmt::format("video {}: frame rate {} is not a positive number", path.string(), fps));
    if (options.crf < 0 || options.crf > 51)
        throw std::invalid_argument(
            fmt::format("video {}: crf {} is outside 0-51", path.string(), options.crf));
    if (options.threads < 0)
        throw std::invalid_argument(
            fmt::format("video {}: threads {} is negative", path.string(), options.threads));

    quiet_libav_logging();
    const AVCodec* h264 = av().avcodec_find_encoder_by_name("libx264");
    if (!h264)
        throw std::runtime_error(fmt::format(
            "cannot write video {}: this libavcodec has no libx264 encoder", path.string()));

    // Built in a local so that a throw below frees everything made so far.
    auto encoder = std::make_unique<Encoder>();
    const int encoded_width = round_up_to_even(width);
    const int encoded_height = round_up_to_even(height);
    const std::filesystem::path partial = path.string() + ".partial";
    // "file:" so that a colon in the path is not taken for a protocol name.
    // The muxer reopens this URL to move the index to the front.
    const std::string url = "file:" + partial.string();

    AVFormatContext* format = nullptr;
    check(av().avformat_alloc_output_context2(&format, nullptr, "mp4", url.c_str()), path,
          "creating the MP4 muxer");
    encoder->format.reset(format);

    encoder->codec.reset(av().avcodec_alloc_context3(h264));
    if (!encoder->codec)
        check(AVERROR(ENOMEM), path, "creating the encoder");
    AVCodecContext& codec = *encoder->codec;
    codec.width = encoded_width;
    codec.height = encoded_height;
    codec.pix_fmt = AV_PIX_FMT_YUV420P;
    codec.time_base = av_inv_q(frame_rate);
    codec.framerate = frame_rate;
    codec.thread_count = options.threads;
    codec.color_range = AVCOL_RANGE_MPEG;
    codec.colorspace = AVCOL_SPC_BT709;
    codec.color_primaries = AVCOL_PRI_BT709;
    codec.color_trc = AVCOL_TRC_BT709;
    // MP4 keeps the H.264 parameter sets in the header, not in the stream.
    if (format->oformat->flags & AVFMT_GLOBALHEADER)
        codec.flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    check(av().av_opt_set(codec.priv_data, "preset", options.preset.c_str(), 0), path,
          "setting the x264 preset");
    check(av().av_opt_set_double(codec.priv_data, "crf", options.crf, 0), path,
          "setting the x264 crf");
    if (!options.mb_tree)
        check(av().av_opt_set(codec.priv_data, "x264-params", "mbtree=0", 0), path,
              "turning off the x264 macroblock tree");
    check(av().avcodec_open2(&codec, h264, nullptr), path,
          fmt::format("opening libx264 (preset '{}', crf {})", options.preset, options.crf));

    encoder->stream = av().avformat_new_stream(format, nullptr);
    if (!encoder->stream)
        check(AVERROR(ENOMEM), path, "adding the video stream");
    check(av().avcodec_parameters_from_context(encoder->stream->codecpar, &codec), path,
          "adding the video stream");
    // A hint: the muxer may refine it, so packets are rescaled to the
    // stream's time base as it stands after the header is written.
    encoder->stream->time_base = codec.time_base;
    encoder->stream->avg_frame_rate = frame_rate;

    check(av().avio_open(&format->pb, url.c_str(), AVIO_FLAG_WRITE), path,
          "creating " + partial.string());
    encoder->partial.path = partial;
    AVDictionary* muxer_options = nullptr;
    av().av_dict_set(&muxer_options, "movflags", "+faststart", 0);
    const int header = av().avformat_write_header(format, &muxer_options);
    av().av_dict_free(&muxer_options);
    check(header, path, "writing the MP4 header");

    encoder->yuv.reset(av().av_frame_alloc());
    encoder->packet.reset(av().av_packet_alloc());
    if (!encoder->yuv || !encoder->packet)
        check(AVERROR(ENOMEM), path, "allocating frame buffers");
    encoder->yuv->format = codec.pix_fmt;
    encoder->yuv->width = encoded_width;
    encoder->yuv->height = encoded_height;
    check(av().av_frame_get_buffer(encoder->yuv.get(), 0), path, "allocating frame buffers");

    encoder->scaler.reset(av().sws_getContext(
        encoded_width, encoded_height, AV_PIX_FMT_RGBA, encoded_width, encoded_height,
        AV_PIX_FMT_YUV420P, SWS_BILINEAR | SWS_ACCURATE_RND, nullptr, nullptr, nullptr));
    if (!encoder->scaler)
        throw std::runtime_error(fmt::format(
            "cannot write video {}: swscale cannot convert RGBA to yuv420p", path.string()));
    // The BT.709 matrix into limited range, matching the tags set above.
    const int* bt709 = av().sws_getCoefficients(SWS_CS_ITU709);
    av().sws_setColorspaceDetails(encoder->scaler.get(), bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);

    if (encoded_width != width || encoded_height != height)
        encoder->padded_rgba.resize(std::size_t(encoded_width) * std::size_t(encoded_height) * 4);
    encoder_ = std::move(encoder);
}

Mp4Writer::~Mp4Writer() {
    try {
        finish();
    } catch (const std::exception& e) {
        // fprintf, not fmt::print: a destructor must not throw, even when
        // stderr is closed.
        std::fprintf(stderr, "sphclip: error: %s\n", e.what());
    }
}

void Mp4Writer::write(const Image& frame) {
    if (!encoder_)
        throw std::logic_error("video " + path_.string() + ": write() after finish()");
    if (frame.width != width_ || frame.height != height_ ||
        frame.rgba.size() != std::size_t(width_) * std::size_t(height_) * 4)
        throw std::invalid_argument(fmt::format("video {}: frame is {}x{}, the video is {}x{}",
                                                path_.string(), frame.width, frame.height, width_,
                                                height_));
    Encoder& encoder = *encoder_;
    AVFrame& yuv = *encoder.yuv;
    try {
        const std::uint8_t* rgba = frame.rgba.data();
        if (!encoder.padded_rgba.empty()) {
            pad_by_replicating_edges(frame, encoder.padded_rgba, yuv.width, yuv.height);
            rgba = encoder.padded_rgba.data();
        }
        // The encoder may still hold the previous frame's buffer.
        check(av().av_frame_make_writable(&yuv), path_, "allocating a frame");
        const int rgba_stride = yuv.width * 4;
        av().sws_scale(encoder.scaler.get(), &rgba, &rgba_stride, 0, yuv.height, yuv.data,
                       yuv.linesize);
        yuv.pts = std::int64_t(frames_written_);
        encoder.encode(&yuv, path_);
        ++frames_written_;
    } catch (...) {
        failed_ = true;
        throw;
    }
}

void Mp4Writer::finish() {
    if (!encoder_)
        return;
    // Taken out first: whatever happens below, the writer is finished, and a
    // throw destroys the encoder, which removes the partial file.
    const std::unique_ptr<Encoder> encoder = std::move(encoder_);
    if (failed_ || frames_written_ == 0)
        return;
    encoder->encode(nullptr, path_);
    check(av().av_write_trailer(encoder->format.get()), path_, "writing the MP4 index");
    check(av().avio_closep(&encoder->format->pb), path_,
          "closing " + encoder->partial.path.string());
    std::error_code error;
    std::filesystem::rename(encoder->partial.path, path_, error);
    if (error)
        throw std::runtime_error(fmt::format("cannot write video {}: renaming {}: {}",
                                             path_.string(), encoder->partial.path.string(),
                                             error.message()));
    encoder->partial.path.clear();
}

bool Mp4Writer::available() {
    return unavailable_reason().empty();
}

std::string Mp4Writer::unavailable_reason() {
    try {
        if (!av().avcodec_find_encoder_by_name("libx264"))
            return "this libavcodec has no libx264 encoder";
        return "";
    } catch (const std::runtime_error& e) {
        return e.what(); // no FFmpeg to load: the library and the loader's reason
    }
}

} // namespace sph
