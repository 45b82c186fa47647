#include "study_ui/video_source.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "framework/core/error.hpp"
#include "study_ui/trial_screen.hpp"

namespace crowdlab::study {

VideoSource::VideoSource(const std::string& path, cv::Rect area, double fallback_fps, double cache_budget_mb)
    : path_(path) {
  if (!cap_.open(path, cv::CAP_FFMPEG)) throw RuntimeError(path + ": cannot open the video");
  const cv::Size native(static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_WIDTH)),
                        static_cast<int>(cap_.get(cv::CAP_PROP_FRAME_HEIGHT)));
  display_ = fit_rect(native, area).size();
  const double fps = cap_.get(cv::CAP_PROP_FPS);
  fps_ = (std::isfinite(fps) && fps > 1.0 && fps < 1000.0) ? fps : fallback_fps;
  const double reported = cap_.get(cv::CAP_PROP_FRAME_COUNT);
  const double bytes_per_frame = 3.0 * display_.width * display_.height;
  const bool cache = reported > 0 && reported * bytes_per_frame <= cache_budget_mb * 1024.0 * 1024.0;
  if (cache) {
    cv::Mat raw;
    while (cap_.read(raw)) frames_.push_back(scaled(raw));
    count_ = static_cast<long>(frames_.size());
    cap_.release();
  } else {
    count_ = static_cast<long>(std::max(0.0, reported));
  }
  if (cache && count_ == 0) throw RuntimeError(path + ": the video has no decodable frame");
}

cv::Mat VideoSource::scaled(const cv::Mat& raw) const {
  if (raw.size() == display_) return raw.clone();
  cv::Mat out;
  cv::resize(raw, out, display_, 0, 0, cv::INTER_AREA);
  return out;
}

const cv::Mat& VideoSource::frame(long k) {
  if (!frames_.empty()) return frames_[static_cast<size_t>(k % count_)];
  long target = count_ > 0 ? k % count_ : k;
  if (target == current_index_ && !current_.empty()) return current_;  // the same frame again (redraw)
  if (target < next_in_stream_) {                                      // wrapped: rewind
    cap_.set(cv::CAP_PROP_POS_FRAMES, 0);
    next_in_stream_ = 0;
  }
  while (next_in_stream_ < target && cap_.grab()) ++next_in_stream_;
  cv::Mat raw;
  if (cap_.read(raw)) {
    current_index_ = next_in_stream_++;
    current_ = scaled(raw);
  } else if (current_.empty()) {
    throw RuntimeError(path_ + ": decoding failed");
  } else {  // unexpected end (frame count was an estimate): rewind next time
    count_ = std::max(1L, next_in_stream_);
  }
  return current_;
}

}  // namespace crowdlab::study
