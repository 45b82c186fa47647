#pragma once
// VideoEncoder: RGBA frames -> H.264 (libx264 through libavcodec), yuv420p, in an MP4 container with
// the moov atom at the front ("movflags=+faststart", so players can start before the whole file has
// arrived). time_base = 1/fps for integer fps (e.g. 1/30; rational approximation otherwise), frame i
// has pts = i, so the clip lasts exactly frames/fps seconds. close() flushes the encoder and writes
// the trailer.
#include <cstdint>
#include <memory>
#include <string>

namespace crowdlab::stimuli {

struct VideoSettings {
  int width = 1920, height = 1080;  ///< even, >= 16 (yuv420p subsamples chroma 2x2)
  double fps = 30.0;
  int crf = 18;                     ///< x264 constant rate factor 0 (lossless) .. 51
  std::string preset = "veryfast";  ///< x264 speed preset (ultrafast .. veryslow)
};

/// Throws InputError when the size is odd or too small, fps not in (0, 240], crf outside 0..51.
void validate_video_settings(const VideoSettings& settings);

/// Wall time of one add_frame(), milliseconds.
struct EncodeTimes {
  double convert_ms = 0.0;  ///< RGBA -> BT.709 yuv420p (libswscale)
  double encode_ms = 0.0;   ///< x264 and muxing
};

class VideoEncoder {
 public:
  /// Opens `path` for writing. Throws InputError for bad settings, RuntimeError when libav fails
  /// (no H.264 encoder, unwritable path).
  VideoEncoder(const std::string& path, const VideoSettings& settings);
  ~VideoEncoder();
  VideoEncoder(const VideoEncoder&) = delete;
  VideoEncoder& operator=(const VideoEncoder&) = delete;

  /// Encodes one frame of width*height RGBA pixels; `bottom_up` when row 0 is the bottom image row
  /// (glReadPixels order).
  EncodeTimes add_frame(const std::uint8_t* rgba, bool bottom_up);
  /// Flushes the encoder and finalises the file. Called by the destructor if not called.
  void close();
  int frames_written() const { return frames_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int frames_ = 0;
};

}  // namespace crowdlab::stimuli
