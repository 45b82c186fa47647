#include "stimuli/video_encoder.hpp"

#include <chrono>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/media/libav.hpp"

namespace crowdlab::stimuli {
void validate_video_settings(const VideoSettings& s) {
  if (s.width < 16 || s.height < 16 || s.width % 2 != 0 || s.height % 2 != 0)
    throw InputError("video size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                     " is invalid: width and height must be even and >= 16 (H.264 yuv420p)");
  if (!(s.fps > 0.0 && s.fps <= 240.0))
    throw InputError("video fps must be in (0, 240], got " + std::to_string(s.fps));
  if (s.crf < 0 || s.crf > 51) throw InputError("video crf must be in 0..51, got " + std::to_string(s.crf));
  // x264's presets (x264 --fullhelp); anything else made the encoder fail at open, as a runtime error.
  static const char* const kPresets[] = {"ultrafast", "superfast", "veryfast", "faster",   "fast",
                                         "medium",    "slow",      "slower",   "veryslow", "placebo"};
  bool known = false;
  for (const char* p : kPresets) known = known || s.preset == p;
  if (!known)
    throw InputError(
        SourceLocation{"", 0, 0, "preset"},
        "unknown x264 preset '" + s.preset +
            "' (ultrafast, superfast, veryfast, faster, fast, medium, slow, slower, veryslow, placebo)");
}

struct VideoEncoder::Impl {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* sws = nullptr;
  bool open = false;
  std::string path;  ///< named by every error: libav's own messages carry no file name

  ~Impl() {
    media::libav().sws_freeContext(sws);
    media::libav().av_packet_free(&packet);
    media::libav().av_frame_free(&frame);
    media::libav().avcodec_free_context(&codec);
    if (format) {
      if (format->pb) media::libav().avio_closep(&format->pb);
      media::libav().avformat_free_context(format);
    }
  }

  void drain(bool flush) {
    for (;;) {
      const int r = media::libav().avcodec_receive_packet(codec, packet);
      if (r == AVERROR(EAGAIN) || (flush && r == AVERROR_EOF)) return;
      if (r < 0) throw RuntimeError(path + ": H.264 encoding failed: " + media::libav_error(r));
      media::libav().av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      const int w = media::libav().av_interleaved_write_frame(format, packet);
      if (w < 0) throw RuntimeError(path + ": write failed: " + media::libav_error(w));
    }
  }
};

VideoEncoder::VideoEncoder(const std::string& path, const VideoSettings& s)
    : impl_(std::make_unique<Impl>()) {
  validate_video_settings(s);
  if (media::libav().av_log_get_level() > AV_LOG_WARNING)
    media::libav().av_log_set_level(AV_LOG_WARNING);  // x264 banners are noise in logs
  Impl& m = *impl_;
  m.path = path;
  if (media::libav().avformat_alloc_output_context2(&m.format, nullptr, "mp4", path.c_str()) < 0 || !m.format)
    throw RuntimeError("cannot create an MP4 container for " + path);
  const AVCodec* codec = media::libav().avcodec_find_encoder_by_name("libx264");
  if (!codec) codec = media::libav().avcodec_find_encoder(AV_CODEC_ID_H264);
  if (!codec) throw RuntimeError("no H.264 encoder in this libavcodec (install libx264 support)");
  m.stream = media::libav().avformat_new_stream(m.format, nullptr);
  m.codec = media::libav().avcodec_alloc_context3(codec);
  if (!m.stream || !m.codec) throw RuntimeError("libav: out of memory");
  const AVRational rate = std::abs(s.fps - std::round(s.fps)) < 1e-9
                              ? AVRational{static_cast<int>(std::lround(s.fps)), 1}
                              : media::libav().av_d2q(s.fps, 100000);
  m.codec->width = s.width;
  m.codec->height = s.height;
  m.codec->pix_fmt = AV_PIX_FMT_YUV420P;
  m.codec->time_base = av_inv_q(rate);
  m.codec->framerate = rate;
  m.codec->gop_size = std::max(1, static_cast<int>(std::lround(2.0 * s.fps)));  // a keyframe every 2 s
  m.codec->color_range = AVCOL_RANGE_MPEG;
  m.codec->colorspace = AVCOL_SPC_BT709;
  m.codec->color_primaries = AVCOL_PRI_BT709;
  m.codec->color_trc = AVCOL_TRC_BT709;
  if (m.format->oformat->flags & AVFMT_GLOBALHEADER) m.codec->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  AVDictionary* codec_opts = nullptr;
  media::libav().av_dict_set(&codec_opts, "crf", std::to_string(s.crf).c_str(), 0);
  media::libav().av_dict_set(&codec_opts, "preset", s.preset.c_str(), 0);
  int r = media::libav().avcodec_open2(m.codec, codec, &codec_opts);
  media::libav().av_dict_free(&codec_opts);
  if (r < 0) throw RuntimeError("cannot open the H.264 encoder: " + media::libav_error(r));
  media::libav().avcodec_parameters_from_context(m.stream->codecpar, m.codec);
  m.stream->time_base = m.codec->time_base;
  m.stream->avg_frame_rate = rate;
  if ((r = media::libav().avio_open(&m.format->pb, path.c_str(), AVIO_FLAG_WRITE)) < 0)
    throw RuntimeError("cannot write " + path + ": " + media::libav_error(r));
  AVDictionary* mux_opts = nullptr;
  media::libav().av_dict_set(&mux_opts, "movflags", "+faststart", 0);
  r = media::libav().avformat_write_header(m.format, &mux_opts);
  media::libav().av_dict_free(&mux_opts);
  if (r < 0) throw RuntimeError("cannot write the MP4 header of " + path + ": " + media::libav_error(r));
  m.open = true;
  m.frame = media::libav().av_frame_alloc();
  m.packet = media::libav().av_packet_alloc();
  m.frame->format = AV_PIX_FMT_YUV420P;
  m.frame->width = s.width;
  m.frame->height = s.height;
  if (!m.frame || !m.packet || media::libav().av_frame_get_buffer(m.frame, 0) < 0)
    throw RuntimeError("libav: out of memory");
  // RGB (full range, sRGB-encoded) -> BT.709 limited-range YUV, the convention players assume for HD.
  // Bilinear: the 2x2 chroma average of yuv420p; bicubic chroma cost 2.5x the CPU for no visible change.
  m.sws = media::libav().sws_getContext(s.width, s.height, AV_PIX_FMT_RGBA, s.width, s.height,
                                        AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (!m.sws) throw RuntimeError("libswscale: cannot convert RGBA to yuv420p");
  const int* coeffs = media::libav().sws_getCoefficients(SWS_CS_ITU709);
  media::libav().sws_setColorspaceDetails(m.sws, coeffs, 1, coeffs, 0, 0, 1 << 16, 1 << 16);
}

VideoEncoder::~VideoEncoder() {
  try {
    close();
  } catch (...) {
    // Destructors must not throw; close() explicitly to see errors.
  }
}

EncodeTimes VideoEncoder::add_frame(const std::uint8_t* rgba, bool bottom_up) {
  using Clock = std::chrono::steady_clock;
  const auto ms_since = [](Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
  };
  EncodeTimes times;
  auto t = Clock::now();
  Impl& m = *impl_;
  if (!m.open) throw RuntimeError("VideoEncoder: add_frame after close");
  if (media::libav().av_frame_make_writable(m.frame) < 0) throw RuntimeError("libav: frame not writable");
  const int stride = 4 * m.codec->width;
  const std::uint8_t* src =
      bottom_up ? rgba + static_cast<std::ptrdiff_t>(stride) * (m.codec->height - 1) : rgba;
  const int src_stride[1] = {bottom_up ? -stride : stride};
  media::libav().sws_scale(m.sws, &src, src_stride, 0, m.codec->height, m.frame->data, m.frame->linesize);
  times.convert_ms = ms_since(t);
  t = Clock::now();
  m.frame->pts = frames_++;
  const int r = media::libav().avcodec_send_frame(m.codec, m.frame);
  if (r < 0) throw RuntimeError(m.path + ": H.264 encoding failed: " + media::libav_error(r));
  m.drain(false);
  times.encode_ms = ms_since(t);
  return times;
}

void VideoEncoder::close() {
  Impl& m = *impl_;
  if (!m.open) return;
  m.open = false;
  const int r = media::libav().avcodec_send_frame(m.codec, nullptr);
  if (r < 0) throw RuntimeError(m.path + ": flushing the H.264 encoder failed: " + media::libav_error(r));
  m.drain(true);
  // libav buffers its writes: a full disk may surface only in the trailer or in the final flush at close,
  // and libav_error() of an AVERROR(errno) is the OS's reason (strerror).
  const int t = media::libav().av_write_trailer(m.format);
  if (t < 0) throw RuntimeError(m.path + ": writing the MP4 trailer failed: " + media::libav_error(t));
  const int c = media::libav().avio_closep(&m.format->pb);
  if (c < 0) throw RuntimeError(m.path + ": write failed: " + media::libav_error(c));
}

}  // namespace crowdlab::stimuli
