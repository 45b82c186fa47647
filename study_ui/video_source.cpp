#include "study_ui/video_source.hpp"

#include <cmath>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "framework/core/error.hpp"
#include "framework/media/video_reader.hpp"
#include "study_ui/trial_screen.hpp"

namespace crowdlab::study {

VideoSource::VideoSource(std::string path, cv::Rect area, double fallback_fps, bool loop, int ahead)
    : path_(std::move(path)),
      area_(area),
      fallback_fps_(fallback_fps),
      loop_(loop),
      ahead_(static_cast<size_t>(std::max(1, ahead))),
      decoder_([this] { decode(); }),
      scaler_([this] { scale(); }) {}

VideoSource::~VideoSource() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  decoder_.join();
  scaler_.join();
}

int scale_interpolation(cv::Size from, cv::Size to) {
  // Bilinear down to half size: 3x faster than area averaging for 1920x1200 -> 1404x878 (35 vs 12
  // fps on the study machine), and without its aliasing only below half size.
  return 2 * to.width >= from.width ? cv::INTER_LINEAR : cv::INTER_AREA;
}

namespace {
constexpr size_t kRawAhead = 2;  // raw frames waiting for the scaler (6.9 MB each at 1920x1200)
}  // namespace

void VideoSource::decode() {
  std::unique_ptr<VideoReader> reader;
  auto fail = [&](const std::string& what) {
    std::lock_guard lock(mutex_);
    error_ = path_ + ": " + what;
    open_ = raw_ended_ = true;
    changed_.notify_all();
  };
  // libavcodec's own threads (0: as many as it likes) keep 1080p playback ahead of the window.
  const auto open = [&] { reader = std::make_unique<VideoReader>(path_, 0); };
  try {
    try {
      open();
    } catch (const RuntimeError&) {
      return fail("cannot open the video");
    }
    const cv::Size native(reader->width(), reader->height());
    const double fps = reader->fps();
    {
      std::lock_guard lock(mutex_);
      display_ = fit_rect(native, area_).size();
      fps_ = (std::isfinite(fps) && fps > 1.0 && fps < 1000.0) ? fps : fallback_fps_;
      count_ = std::max(0L, reader->frame_count_estimate());
      open_ = true;
    }
    changed_.notify_all();
    long index = 0, in_pass = 0;
    while (true) {
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return stop_ || raw_.size() < kRawAhead; });
        if (stop_) return;
      }
      bool late = false;
      {
        std::lock_guard lock(mutex_);
        late = index < wanted_;
      }
      bool got = false;
      try {
        got = reader->next();
      } catch (const RuntimeError&) {
        got = false;
      }
      // A frame the window has already passed is decoded (the next ones depend on it) but neither
      // converted nor scaled: when the clip falls behind, it catches up at the decoder's pace.
      if (got && late) {
        ++index, ++in_pass;
        continue;
      }
      if (!got) {
        if (in_pass == 0) return fail(index == 0 ? "the video has no decodable frame" : "decoding failed");
        {
          std::lock_guard lock(mutex_);
          count_ = in_pass;  // the real length (the container's count is an estimate)
          if (!loop_) {
            raw_ended_ = true;
            changed_.notify_all();
            return;
          }
        }
        // Open the file again rather than seek: a seek lands on a key frame, not necessarily frame 0.
        reader.reset();
        try {
          open();
        } catch (const RuntimeError&) {
          return fail("cannot reopen the video to loop it");
        }
        in_pass = 0;
        continue;
      }
      cv::Mat raw(reader->height(), reader->width(), CV_8UC3);
      reader->copy_bgr(raw.data, raw.step);
      {
        std::lock_guard lock(mutex_);
        raw_.emplace_back(index++, std::move(raw));
      }
      ++in_pass;
      changed_.notify_all();
    }
  } catch (const std::exception& e) {
    fail(std::string("decoding failed: ") + e.what());
  }
}

void VideoSource::scale() {
  while (true) {
    std::pair<long, cv::Mat> raw;
    cv::Size display;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] {
        return stop_ || (!raw_.empty() && queue_.size() < ahead_) || (raw_.empty() && raw_ended_);
      });
      if (stop_) return;
      if (raw_.empty()) {  // the decoder is done and every frame is scaled
        ended_ = true;
        changed_.notify_all();
        return;
      }
      raw = std::move(raw_.front());
      raw_.pop_front();
      display = display_;
      if (raw.first < wanted_) {  // already passed by the window: not worth scaling
        changed_.notify_all();
        continue;
      }
    }
    changed_.notify_all();  // room for the decoder
    cv::Mat scaled;
    try {
      if (raw.second.size() == display)
        scaled = raw.second;
      else
        cv::resize(raw.second, scaled, display, 0, 0, scale_interpolation(raw.second.size(), display));
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex_);
      error_ = path_ + ": scaling failed: " + e.what();
      ended_ = raw_ended_ = true;
      changed_.notify_all();
      return;
    }
    {
      std::lock_guard lock(mutex_);
      queue_.emplace_back(raw.first, std::move(scaled));
    }
    changed_.notify_all();
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
  // Played once, the last frame stays on screen past the end: it is never skipped.
  wanted_ = std::max(wanted_, loop_ || count_ <= 0 ? k : std::min(k, count_ - 1));
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
