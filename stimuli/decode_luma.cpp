#include "stimuli/decode_luma.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <memory>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

struct Decoder {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  int stream = -1;
  ~Decoder() {
    av_frame_free(&frame);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }
};

void open(Decoder& d, const std::string& path) {
  if (!d.packet || !d.frame) throw RuntimeError("libav: out of memory");
  if (avformat_open_input(&d.format, path.c_str(), nullptr, nullptr) < 0)
    throw RuntimeError("cannot open video " + path);
  if (avformat_find_stream_info(d.format, nullptr) < 0) throw RuntimeError("cannot read video " + path);
  const AVCodec* decoder = nullptr;
  d.stream = av_find_best_stream(d.format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (d.stream < 0 || !decoder) throw RuntimeError(path + ": no decodable video stream");
  d.codec = avcodec_alloc_context3(decoder);
  if (!d.codec || avcodec_parameters_to_context(d.codec, d.format->streams[d.stream]->codecpar) < 0 ||
      avcodec_open2(d.codec, decoder, nullptr) < 0)
    throw RuntimeError(path + ": cannot open the video decoder");
}

void take_frames(Decoder& d, std::vector<cv::Mat>& out, const std::string& path) {
  for (;;) {
    const int r = avcodec_receive_frame(d.codec, d.frame);
    if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
    if (r < 0) throw RuntimeError(path + ": decoding failed");
    const cv::Mat y(d.frame->height, d.frame->width, CV_8UC1, d.frame->data[0],
                    static_cast<size_t>(d.frame->linesize[0]));
    out.push_back(y.clone());
  }
}

}  // namespace

std::vector<cv::Mat> decode_luma(const std::string& path) {
  Decoder d;
  open(d, path);
  std::vector<cv::Mat> frames;
  while (av_read_frame(d.format, d.packet) >= 0) {
    const bool ours = d.packet->stream_index == d.stream;
    const int r = ours ? avcodec_send_packet(d.codec, d.packet) : 0;
    av_packet_unref(d.packet);
    if (r < 0) throw RuntimeError(path + ": decoding failed");
    if (ours) take_frames(d, frames, path);
  }
  avcodec_send_packet(d.codec, nullptr);  // flush
  take_frames(d, frames, path);
  return frames;
}

cv::Mat rgba_to_luma_bt709(const std::uint8_t* rgba, int width, int height, bool bottom_up) {
  cv::Mat y(height, width, CV_8UC1);
  for (int row = 0; row < height; ++row) {
    const std::uint8_t* src = rgba + static_cast<size_t>(bottom_up ? height - 1 - row : row) * 4 * width;
    std::uint8_t* dst = y.ptr<std::uint8_t>(row);
    for (int x = 0; x < width; ++x, src += 4) {
      const double luma = 0.2126 * src[0] + 0.7152 * src[1] + 0.0722 * src[2];
      dst[x] = static_cast<std::uint8_t>(16.0 + 219.0 * luma / 255.0 + 0.5);
    }
  }
  return y;
}

}  // namespace crowdlab::stimuli
