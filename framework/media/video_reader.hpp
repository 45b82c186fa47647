#pragma once
// VideoReader: the frames of a video file, one at a time, as libavformat demuxes and libavcodec decodes
// them (FFmpeg 5.1, Debian 12). Used by the render-quality check (the luma planes the encoder wrote) and
// by the study window (BGR frames to show).
//
// Why not OpenCV's cv::VideoCapture: libopencv_videoio loads about 240 shared libraries (GStreamer,
// GDAL, ...), which every start of the `crowdlab` binary paid (~0.2 s of its ~0.27 s), although crowdlab
// decodes through libavcodec either way (issue 31, session 17; docs/building.md).
//
// Input: the path of any container and codec libavformat/libavcodec read. Output, per frame: the decoded
// picture's luma plane (for YUV and grey formats: plane 0, 8 bit) or the picture converted to packed
// 8-bit BGR by libswscale. Errors: RuntimeError naming the file (cannot open, no video stream, decoding
// failed).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace crowdlab {

class VideoReader {
 public:
  /// Opens `path` and its best video stream. `decoder_threads` 0 lets libavcodec choose (frame threads
  /// for playback); 1 decodes on the calling thread.
  explicit VideoReader(const std::string& path, int decoder_threads = 1);
  ~VideoReader();
  VideoReader(const VideoReader&) = delete;
  VideoReader& operator=(const VideoReader&) = delete;

  /// The current frame's size in pixels (before the first frame: the stream's).
  int width() const;
  int height() const;
  /// Frames per second from the stream's average (or real) frame rate; 0 when the file does not say.
  double fps() const;
  /// The container's frame count (an estimate for some containers); 0 when unknown.
  long frame_count_estimate() const;

  /// Decodes the next frame; false after the last. The frame stays current until the next call.
  bool next();
  /// The current frame's luma plane copied to `dst` (width() bytes per row, `dst_stride` apart).
  void copy_luma(std::uint8_t* dst, std::size_t dst_stride) const;
  /// The current frame converted to packed BGR (3 bytes per pixel) into `dst`, `dst_stride` apart.
  void copy_bgr(std::uint8_t* dst, std::size_t dst_stride);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace crowdlab
