#pragma once
// FFmpeg for the MP4 writer and the tests that decode its files back: its
// functions, from its libraries loaded when the first video is written
// (platform/shared_library.hpp says why not at start), and deleters for its
// objects held in std::unique_ptr, so every exit path frees them.

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/dict.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libavutil/rational.h>
#include <libswscale/swscale.h>
}

namespace sph::libav {

// The functions sphclip calls, by library (avcodec is libavcodec.so.N, N
// the major version of the headers built against).
#define SPHCLIP_LIBAV_FUNCTIONS(X)                                                                 \
    X(avcodec, avcodec_alloc_context3)                                                             \
    X(avcodec, avcodec_find_encoder_by_name)                                                       \
    X(avcodec, avcodec_free_context)                                                               \
    X(avcodec, avcodec_open2)                                                                      \
    X(avcodec, avcodec_parameters_from_context)                                                    \
    X(avcodec, avcodec_receive_packet)                                                             \
    X(avcodec, avcodec_send_frame)                                                                 \
    X(avcodec, av_packet_alloc)                                                                    \
    X(avcodec, av_packet_free)                                                                     \
    X(avcodec, av_packet_rescale_ts)                                                               \
    X(avformat, avformat_alloc_output_context2)                                                    \
    X(avformat, avformat_free_context)                                                             \
    X(avformat, avformat_new_stream)                                                               \
    X(avformat, avformat_write_header)                                                             \
    X(avformat, av_interleaved_write_frame)                                                        \
    X(avformat, av_write_trailer)                                                                  \
    X(avformat, avio_closep)                                                                       \
    X(avformat, avio_open)                                                                         \
    X(avutil, av_d2q)                                                                              \
    X(avutil, av_dict_free)                                                                        \
    X(avutil, av_dict_set)                                                                         \
    X(avutil, av_frame_alloc)                                                                      \
    X(avutil, av_frame_free)                                                                       \
    X(avutil, av_frame_get_buffer)                                                                 \
    X(avutil, av_frame_make_writable)                                                              \
    X(avutil, av_log_set_level)                                                                    \
    X(avutil, av_opt_set)                                                                          \
    X(avutil, av_opt_set_double)                                                                   \
    X(avutil, av_strerror)                                                                         \
    X(swscale, sws_freeContext)                                                                    \
    X(swscale, sws_getCoefficients)                                                                \
    X(swscale, sws_getContext)                                                                     \
    X(swscale, sws_scale)                                                                          \
    X(swscale, sws_setColorspaceDetails)

struct Functions {
#define SPHCLIP_LIBAV_POINTER(library, name) decltype(&::name) name;
    SPHCLIP_LIBAV_FUNCTIONS(SPHCLIP_LIBAV_POINTER)
#undef SPHCLIP_LIBAV_POINTER
};

// FFmpeg's functions, its libraries loaded on the first call. Throws
// std::runtime_error naming the library or function it could not load.
const Functions& functions();

struct CodecContextDeleter {
    void operator()(AVCodecContext* context) const { functions().avcodec_free_context(&context); }
};
struct FrameDeleter {
    void operator()(AVFrame* frame) const { functions().av_frame_free(&frame); }
};
struct PacketDeleter {
    void operator()(AVPacket* packet) const { functions().av_packet_free(&packet); }
};
struct ScalerDeleter {
    void operator()(SwsContext* scaler) const { functions().sws_freeContext(scaler); }
};

} // namespace sph::libav
