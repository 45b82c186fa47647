#pragma once
// VideoSource: the frames of one stimulus clip for the study window, streamed. A decoder thread opens
// the clip (cv::VideoCapture, FFmpeg) and decodes ahead into a small bounded queue of raw frames; a
// scaler thread scales them to their on-screen size into a bounded queue of `ahead` frames; the window
// takes them in order. Two threads, because decoding and scaling a 1920x1200 frame each take about as
// long as a 60 fps frame period on the study machine (docs/study.md): pipelined, they keep up. Memory is
// bounded by `ahead` frames (plus the one on screen), whatever the clip's length: a 210-frame 1920x1200 clip
// no longer has to be decoded whole (about 776 MB at 1404x878) before it starts (issue 29, finding 12).
// Constructing a VideoSource returns at once, so the window can prefetch the next trial's clip while the
// participant answers: its first frames are then ready at the next onset.
//
// Looping: frame indices count on across loops (frame k shows the clip's frame k mod frame_count());
// at the end of the file the thread opens it again and keeps decoding ahead, so the wrap costs no
// frame. Play-once (loop = false): past the last frame, frame(k) returns the last frame.
// frame(k) must be called with non-decreasing k; frames before k are discarded (the caller counts them
// as dropped, as it schedules frames against its clock). When the decoder is behind, frame(k) waits.
#include <condition_variable>
#include <deque>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <thread>
#include <utility>

namespace crowdlab::study {

/// The interpolation that scales a frame of size `from` to `to` (cv::INTER_*).
int scale_interpolation(cv::Size from, cv::Size to);

class VideoSource {
 public:
  /// Starts decoding `path` on a thread. Frames are scaled to fit `area` with their aspect ratio
  /// (fit_rect); `fallback_fps` is used when the container reports none. Errors (a file that cannot be
  /// opened or holds no decodable frame) surface as RuntimeError from the first accessor.
  VideoSource(std::string path, cv::Rect area, double fallback_fps, bool loop, int ahead = 6);
  ~VideoSource();
  VideoSource(const VideoSource&) = delete;
  VideoSource& operator=(const VideoSource&) = delete;

  const std::string& path() const { return path_; }
  /// Frame rate (the container's, else the fallback); waits until the clip is open.
  double fps();
  /// Frames of one pass: the container's count, corrected when the end is found earlier or later.
  long frame_count();
  /// Frame k of the presentation (see above), scaled to the display size; waits until it is decoded.
  const cv::Mat& frame(long k);
  /// Decoded frames waiting in the queue (at most `ahead`): what the clip costs in memory.
  long frames_buffered();

 private:
  void decode();
  void scale();
  void wait_open(std::unique_lock<std::mutex>& lock);
  std::string path_;
  cv::Rect area_;
  double fallback_fps_;
  bool loop_;
  size_t ahead_;

  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = false, ended_ = false, stop_ = false;
  std::string error_;
  double fps_ = 30.0;
  long count_ = 0;
  cv::Size display_;
  long wanted_ = 0;                             // the highest index the window asked for
  std::deque<std::pair<long, cv::Mat>> raw_;    // decoded, not yet scaled (at most kRawAhead)
  bool raw_ended_ = false;                      // the decoder is done (end of a play-once clip, or failed)
  std::deque<std::pair<long, cv::Mat>> queue_;  // (presentation index, frame), ascending
  long current_index_ = -1;
  cv::Mat current_;
  std::thread decoder_;  // last: started once every member above exists
  std::thread scaler_;
};

}  // namespace crowdlab::study
