#include "framework/media/video_reader.hpp"

#include <cstring>

#include "framework/core/error.hpp"
#include "framework/media/libav.hpp"

namespace crowdlab {

struct VideoReader::State {
  std::string path;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = media::libav().av_packet_alloc();
  AVFrame* frame = media::libav().av_frame_alloc();
  SwsContext* to_bgr = nullptr;
  int stream = -1;
  bool have_frame = false;
  bool flushed = false;  // the end of the file reached and the decoder told so
  ~State() {
    media::libav().sws_freeContext(to_bgr);
    media::libav().av_frame_free(&frame);
    media::libav().av_packet_free(&packet);
    media::libav().avcodec_free_context(&codec);
    media::libav().avformat_close_input(&format);
  }
};

VideoReader::VideoReader(const std::string& path, int decoder_threads) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.path = path;
  if (!s.packet || !s.frame) throw RuntimeError(path + ": out of memory opening the video");
  if (media::libav().avformat_open_input(&s.format, path.c_str(), nullptr, nullptr) < 0)
    throw RuntimeError("cannot open video " + path);
  if (media::libav().avformat_find_stream_info(s.format, nullptr) < 0)
    throw RuntimeError("cannot read video " + path);
  const AVCodec* decoder = nullptr;
  s.stream = media::libav().av_find_best_stream(s.format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (s.stream < 0 || !decoder) throw RuntimeError(path + ": no decodable video stream");
  s.codec = media::libav().avcodec_alloc_context3(decoder);
  if (!s.codec ||
      media::libav().avcodec_parameters_to_context(s.codec, s.format->streams[s.stream]->codecpar) < 0)
    throw RuntimeError(path + ": cannot open the video decoder");
  s.codec->thread_count = decoder_threads;
  if (media::libav().avcodec_open2(s.codec, decoder, nullptr) < 0)
    throw RuntimeError(path + ": cannot open the video decoder");
}

VideoReader::~VideoReader() = default;

int VideoReader::width() const {
  return state_->have_frame ? state_->frame->width : state_->codec->width;
}
int VideoReader::height() const {
  return state_->have_frame ? state_->frame->height : state_->codec->height;
}

double VideoReader::fps() const {
  const AVStream* stream = state_->format->streams[state_->stream];
  for (const AVRational rate : {stream->avg_frame_rate, stream->r_frame_rate})
    if (rate.num > 0 && rate.den > 0) return av_q2d(rate);
  return 0.0;
}

long VideoReader::frame_count_estimate() const {
  const AVStream* stream = state_->format->streams[state_->stream];
  if (stream->nb_frames > 0) return static_cast<long>(stream->nb_frames);
  const double seconds =
      stream->duration > 0           ? static_cast<double>(stream->duration) * av_q2d(stream->time_base)
      : state_->format->duration > 0 ? static_cast<double>(state_->format->duration) / AV_TIME_BASE
                                     : 0.0;
  return static_cast<long>(seconds * fps() + 0.5);
}

bool VideoReader::next() {
  State& s = *state_;
  s.have_frame = false;
  for (;;) {
    const int received = media::libav().avcodec_receive_frame(s.codec, s.frame);
    if (received == 0) return s.have_frame = true;
    if (received == AVERROR_EOF) return false;
    if (received != AVERROR(EAGAIN)) throw RuntimeError(s.path + ": decoding failed");
    if (s.flushed) return false;
    if (media::libav().av_read_frame(s.format, s.packet) <
        0) {  // the end: drain the frames the decoder holds
      media::libav().avcodec_send_packet(s.codec, nullptr);
      s.flushed = true;
      continue;
    }
    const bool ours = s.packet->stream_index == s.stream;
    const int sent = ours ? media::libav().avcodec_send_packet(s.codec, s.packet) : 0;
    media::libav().av_packet_unref(s.packet);
    if (sent < 0) throw RuntimeError(s.path + ": decoding failed");
  }
}

void VideoReader::copy_luma(std::uint8_t* dst, std::size_t dst_stride) const {
  const AVFrame* f = state_->frame;
  const AVPixFmtDescriptor* desc = media::libav().av_pix_fmt_desc_get(static_cast<AVPixelFormat>(f->format));
  if (!state_->have_frame || !desc || (desc->flags & AV_PIX_FMT_FLAG_RGB) || desc->comp[0].depth != 8)
    throw RuntimeError(state_->path + ": the decoded frames have no 8-bit luma plane");
  for (int row = 0; row < f->height; ++row)
    std::memcpy(dst + row * dst_stride, f->data[0] + static_cast<std::ptrdiff_t>(row) * f->linesize[0],
                static_cast<std::size_t>(f->width));
}

void VideoReader::copy_bgr(std::uint8_t* dst, std::size_t dst_stride) {
  State& s = *state_;
  const AVFrame* f = s.frame;
  if (!s.have_frame) throw RuntimeError(s.path + ": no decoded frame to convert");
  // Bicubic chroma upsampling, as OpenCV's FFmpeg reader (the study window's decoder before session 17).
  s.to_bgr = media::libav().sws_getCachedContext(s.to_bgr, f->width, f->height,
                                                 static_cast<AVPixelFormat>(f->format), f->width, f->height,
                                                 AV_PIX_FMT_BGR24, SWS_BICUBIC, nullptr, nullptr, nullptr);
  if (!s.to_bgr) throw RuntimeError(s.path + ": cannot convert the decoded frames to BGR");
  std::uint8_t* planes[4] = {dst, nullptr, nullptr, nullptr};
  const int strides[4] = {static_cast<int>(dst_stride), 0, 0, 0};
  media::libav().sws_scale(s.to_bgr, f->data, f->linesize, 0, f->height, planes, strides);
}

}  // namespace crowdlab
