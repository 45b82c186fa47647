#pragma once
// VideoSource: the frames of one stimulus clip for the study window. Short clips are decoded once
// into memory, already scaled to their on-screen size (then looping is a modulo, with no decoder
// seek at the seam); clips too large for the memory budget are streamed with cv::VideoCapture and
// rewound at the end. frame(k) must be called with non-decreasing k within a loop (streaming grabs
// and discards skipped frames to stay in step).
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

namespace crowdlab::study {

class VideoSource {
 public:
  /// Opens `path`; throws RuntimeError when it cannot be opened or decodes no frame.
  /// Frames are scaled to fit `area` with their aspect ratio (fit_rect); `fallback_fps` is used when
  /// the container reports none.
  VideoSource(const std::string& path, cv::Rect area, double fallback_fps, double cache_budget_mb);
  double fps() const { return fps_; }
  long frame_count() const { return count_; }
  bool in_memory() const { return !frames_.empty(); }
  /// The frame with index k modulo frame_count(), scaled to the display size.
  const cv::Mat& frame(long k);

 private:
  cv::Mat scaled(const cv::Mat& raw) const;
  std::string path_;
  cv::Size display_;
  double fps_ = 30.0;
  long count_ = 0;
  std::vector<cv::Mat> frames_;
  cv::VideoCapture cap_;
  long next_in_stream_ = 0;
  long current_index_ = -1;
  cv::Mat current_;
};

}  // namespace crowdlab::study
