#pragma once
// FFmpeg's libraries (libavutil, libavcodec, libavformat, libswscale), loaded when a video is first
// written or read instead of when the program starts (issue 31).
//
// Why: linked, libavcodec and libavformat bring about 130 shared libraries (every codec, TLS, network
// protocols) whose loading cost every `crowdlab` command ~127 ms of CPU of its ~190 ms start-up on a
// 2-core VM (a program that only links them: 127 ms; `crowdlab version`: 192 ms), and ~300 ms under the
// sanitizers: `validate`, `--help` and each of the tests' hundreds of CLI runs paid it for nothing.
//
// The table holds a pointer to each function the product calls, typed from the headers it was compiled
// against and resolved with dlopen/dlsym from those headers' sonames (lib<name>.so.<VERSION_MAJOR>), so the
// ABI is the one the headers describe, as when linked. Inline helpers (av_q2d, av_inv_q) and macros
// (AVERROR) come from the headers as before.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <string>

namespace crowdlab::media {

// X(function) for every libav function the product calls, by library.
// clang-format off
#define CROWDLAB_LIBAV_FUNCTIONS(X)                                                                     \
  /* libavutil */                                                                                       \
  X(av_strerror) X(av_log_get_level) X(av_log_set_level) X(av_dict_set) X(av_dict_free) X(av_d2q)      \
  X(av_frame_alloc) X(av_frame_free) X(av_frame_get_buffer) X(av_frame_make_writable)                   \
  X(av_pix_fmt_desc_get)                                                                                \
  /* libavcodec */                                                                                      \
  X(avcodec_find_encoder_by_name) X(avcodec_find_encoder) X(avcodec_alloc_context3)                     \
  X(avcodec_free_context) X(avcodec_open2) X(avcodec_parameters_from_context)                           \
  X(avcodec_parameters_to_context) X(avcodec_send_frame) X(avcodec_receive_packet)                      \
  X(avcodec_send_packet) X(avcodec_receive_frame) X(av_packet_alloc) X(av_packet_free)                  \
  X(av_packet_unref) X(av_packet_rescale_ts)                                                            \
  /* libavformat */                                                                                     \
  X(avformat_alloc_output_context2) X(avformat_new_stream) X(avformat_free_context) X(avio_open)        \
  X(avio_closep) X(avformat_write_header) X(av_interleaved_write_frame) X(av_write_trailer)             \
  X(avformat_open_input) X(avformat_find_stream_info) X(av_find_best_stream) X(avformat_close_input)    \
  X(av_read_frame)                                                                                      \
  /* libswscale */                                                                                      \
  X(sws_getContext) X(sws_getCachedContext) X(sws_freeContext) X(sws_scale) X(sws_getCoefficients)      \
  X(sws_setColorspaceDetails)
// clang-format on

/// The libav functions, each a pointer of its declared type.
struct Libav {
#define CROWDLAB_LIBAV_POINTER(name) decltype(&::name) name = nullptr;
  CROWDLAB_LIBAV_FUNCTIONS(CROWDLAB_LIBAV_POINTER)
#undef CROWDLAB_LIBAV_POINTER
};

/// The table, loaded on the first call (thread-safe). RuntimeError naming the library or the function and
/// the loader's reason when one cannot be loaded (a later call tries again).
const Libav& libav();

/// libav's message for an error code (av_strerror).
std::string libav_error(int code);

}  // namespace crowdlab::media
