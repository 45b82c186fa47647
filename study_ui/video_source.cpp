#include "study_ui/video_source.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "framework/core/error.hpp"
#include "study_ui/trial_screen.hpp"

namespace crowdlab::study {

VideoSource::VideoSource(std::string path, cv::Rect area, double fallback_fps, bool loop, int ahead)
    : path_(std::move(path)),
      area_(area),
      fallback_fps_(fallback_fps),
      loop_(loop),
      ahead_(static_cast<size_t>(std::max(1, ahead))),
      thread_([this] { decode(); }) {}

VideoSource::~VideoSource() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void VideoSource::decode() {
  cv::VideoCapture cap;
  cv::Size display;
  auto fail = [&](const std::string& what) {
    std::lock_guard lock(mutex_);
    error_ = path_ + ": " + what;
    open_ = ended_ = true;
    changed_.notify_all();
  };
  try {
    if (!cap.open(path_, cv::CAP_FFMPEG)) return fail("cannot open the video");
    const cv::Size native(static_cast<int>(cap.get(cv::CAP_PROP_FRAME_WIDTH)),
                          static_cast<int>(cap.get(cv::CAP_PROP_FRAME_HEIGHT)));
    display = fit_rect(native, area_).size();
    const double fps = cap.get(cv::CAP_PROP_FPS);
    {
      std::lock_guard lock(mutex_);
      fps_ = (std::isfinite(fps) && fps > 1.0 && fps < 1000.0) ? fps : fallback_fps_;
      count_ = static_cast<long>(std::max(0.0, cap.get(cv::CAP_PROP_FRAME_COUNT)));
      open_ = true;
    }
    changed_.notify_all();
    long index = 0, in_pass = 0;
    cv::Mat raw;
    while (true) {
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stop_ || queue_.size() < ahead_; });
        if (stop_) return;
      }
      if (!cap.read(raw)) {
        if (in_pass == 0) return fail(index == 0 ? "the video has no decodable frame" : "decoding failed");
        {
          std::lock_guard lock(mutex_);
          count_ = in_pass;  // the real length (the container's count is an estimate)
          if (!loop_) {
            ended_ = true;
            changed_.notify_all();
            return;
          }
        }
        // Open the file again rather than seek: a seek lands on a key frame, not necessarily frame 0.
        cap.release();
        if (!cap.open(path_, cv::CAP_FFMPEG)) return fail("cannot reopen the video to loop it");
        in_pass = 0;
        continue;
      }
      cv::Mat scaled;
      if (raw.size() == display)
        scaled = raw.clone();
      else
        cv::resize(raw, scaled, display, 0, 0, cv::INTER_AREA);
      {
        std::lock_guard lock(mutex_);
        queue_.emplace_back(index++, std::move(scaled));
      }
      ++in_pass;
      changed_.notify_all();
    }
  } catch (const std::exception& e) {
    fail(std::string("decoding failed: ") + e.what());
  }
}

void VideoSource::wait_open(std::unique_lock<std::mutex>& lock) {
  changed_.wait(lock, [&] { return open_; });
  if (!error_.empty() && queue_.empty() && current_.empty()) throw RuntimeError(error_);
}

double VideoSource::fps() {
  std::unique_lock lock(mutex_);
  wait_open(lock);
  return fps_;
}

long VideoSource::frame_count() {
  std::unique_lock lock(mutex_);
  wait_open(lock);
  return count_;
}

long VideoSource::frames_buffered() {
  std::lock_guard lock(mutex_);
  return static_cast<long>(queue_.size());
}

const cv::Mat& VideoSource::frame(long k) {
  if (k == current_index_ && !current_.empty()) return current_;  // the same frame again (a redraw)
  std::unique_lock lock(mutex_);
  wait_open(lock);
  while (true) {
    while (!queue_.empty() && queue_.front().first < k) {  // late: skipped, but kept as the last one
      current_index_ = queue_.front().first;
      current_ = std::move(queue_.front().second);
      queue_.pop_front();
    }
    if (!queue_.empty()) {
      current_index_ = queue_.front().first;
      current_ = std::move(queue_.front().second);
      queue_.pop_front();
      changed_.notify_all();  // room for the decoder
      return current_;
    }
    if (ended_) {  // past the end of a play-once clip (or a failure after some frames): hold the last
      if (current_.empty()) throw RuntimeError(error_.empty() ? path_ + ": no frame" : error_);
      return current_;
    }
    changed_.notify_all();
    changed_.wait(lock, [&] { return !queue_.empty() || ended_; });
  }
}

}  // namespace crowdlab::study
