#include "study_ui/window_presenter.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <opencv2/highgui.hpp>
#include <optional>

#include "framework/core/error.hpp"
#include "framework/media/png_image.hpp"
#include "study_ui/frame_interval_stats.hpp"
#include "study_ui/scale_keys.hpp"
#include "study_ui/text_renderer.hpp"
#include "study_ui/trial_screen.hpp"
#include "study_ui/video_source.hpp"
#include "study_ui/x11_screen_size.hpp"

namespace crowdlab::study {
namespace {

using Clock = std::chrono::steady_clock;
constexpr const char* kWindow = "crowdlab study";
constexpr int kEsc = 27;
constexpr double kDebounceMs = 300.0;

bool is_enter(int key) {
  return key == 13 || key == 10 || key == 0xff0d || key == 0xff8d || key == 32;
}

/// Digit 0..9 from the top row or the keypad, else -1.
int digit_of(int key) {
  if (key >= '0' && key <= '9') return key - '0';
  if (key >= 0xffb0 && key <= 0xffb9) return key - 0xffb0;
  return -1;
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/// Polls the window's image rectangle for up to `tries` x 50 ms until `done` holds (the window system
/// applies full screen and resizes asynchronously).
template <typename Done>
cv::Rect poll_window_rect(int tries, Done done) {
  cv::Rect r;
  for (int i = 0; i < tries; ++i) {
    cv::waitKey(50);
    r = cv::getWindowImageRect(kWindow);
    if (i >= 4 && done(r)) break;
  }
  return r;
}

/// Full screen: asks the window system; when it does not comply (a bare X server, no window manager)
/// the window covers the X screen itself, undecorated at (0, 0) with the screen's size. Returns the
/// canvas size; throws RuntimeError when the screen is not covered and options.require_fullscreen.
cv::Size go_fullscreen(const WindowOptions& options) {
  const std::optional<std::pair<int, int>> screen = x11_screen_size();
  const cv::Size screen_size = screen ? cv::Size(screen->first, screen->second) : cv::Size(640, 480);
  auto covers = [&](const cv::Rect& r) {
    return screen ? r.width >= screen_size.width && r.height >= screen_size.height
                  : r.width >= 800 && r.height >= 600;
  };
  // A canvas of the screen's size, so that the aspect-keeping window does not letterbox it.
  cv::imshow(kWindow, cv::Mat(screen_size, CV_8UC3, cv::Scalar(236, 233, 230)));
  cv::setWindowProperty(kWindow, cv::WND_PROP_FULLSCREEN, cv::WINDOW_FULLSCREEN);
  cv::Rect r = poll_window_rect(60, covers);
  if (!covers(r) && screen) {
    cv::moveWindow(kWindow, 0, 0);
    cv::resizeWindow(kWindow, screen_size.width, screen_size.height);
    r = poll_window_rect(40, covers);
    if (covers(r))
      spdlog::info(
          "the window system did not apply full screen (no window manager?): the window covers the "
          "{}x{} X screen itself",
          screen_size.width, screen_size.height);
  }
  if (covers(r)) return r.size();
  const std::string screen_text =
      screen ? std::to_string(screen_size.width) + "x" + std::to_string(screen_size.height)
             : "of unknown size";
  if (options.require_fullscreen)
    throw RuntimeError("--require-fullscreen: the study window could not cover the screen (window " +
                       std::to_string(r.width) + "x" + std::to_string(r.height) + ", screen " + screen_text +
                       "); run on a desktop or an X server, or drop --require-fullscreen");
  if (r.width >= 800 && r.height >= 600) {  // e.g. a desktop that keeps its panels: usable, say so
    spdlog::warn("the window does not cover the screen (window {}x{}, screen {}); using it as it is", r.width,
                 r.height, screen_text);
    return r.size();
  }
  spdlog::warn("full screen was not applied (window {}x{}, screen {}); using a {}x{} window", r.width,
               r.height, screen_text, options.width, options.height);
  cv::resizeWindow(kWindow, options.width, options.height);
  return {options.width, options.height};
}

}  // namespace

struct WindowPresenter::Impl {
  WindowOptions options;
  TextRenderer text;
  cv::Size canvas_size;
  std::deque<cv::Point> clicks;
  std::unique_ptr<VideoSource> prefetched;  ///< the next trial's clip, decoding its first frames

  explicit Impl(const WindowOptions& o) : options(o), text(o.font_path) {}

  static void on_mouse(int event, int x, int y, int, void* self) {
    if (event == cv::EVENT_LBUTTONDOWN) static_cast<Impl*>(self)->clicks.emplace_back(x, y);
  }
  bool window_closed() const {
    try {
      return cv::getWindowProperty(kWindow, cv::WND_PROP_VISIBLE) < 1.0;
    } catch (const cv::Exception&) {
      return true;
    }
  }
  /// Drops every key and click the window system has queued (typed during the previous trial's
  /// Next or while this clip loaded), so that only input made after the stimulus onset answers this
  /// trial. Returns the onset: the moment the first frame has been handed over and the queue is empty.
  Clock::time_point discard_pending_input() {
    for (int i = 0; i < 1000 && cv::pollKey() != -1; ++i) {
    }
    clicks.clear();
    return Clock::now();
  }
  /// Keeps the window responsive (events processed, input discarded later) until `t`.
  void wait_until(Clock::time_point t) const {
    while (Clock::now() < t) {
      const double left_ms = std::chrono::duration<double, std::milli>(t - Clock::now()).count();
      cv::waitKey(std::max(1, std::min(10, static_cast<int>(left_ms))));
    }
  }
  void snapshot(const cv::Mat& canvas, const std::string& name) const {
    if (options.snapshot_dir.empty()) return;
    std::filesystem::create_directories(options.snapshot_dir);
    const std::string path = (std::filesystem::path(options.snapshot_dir) / (name + ".png")).string();
    try {  // a snapshot is a record for the experimenter: a full disk must not end the session
      write_png_file(path, canvas.data, canvas.cols, canvas.rows, canvas.channels(), canvas.step);
    } catch (const std::exception& e) {
      spdlog::warn("snapshot not written: {}", e.what());
    }
  }
};

WindowPresenter::WindowPresenter(const WindowOptions& options) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0'))
    throw RuntimeError(
        "no display (DISPLAY is not set): run on a desktop, under Xvfb, or use --responses/--simulate");
  impl_ = std::make_unique<Impl>(options);
  // GUI_NORMAL: no Qt toolbar or status bar (Debian's OpenCV highgui uses the Qt backend), so the
  // canvas fills the window and mouse coordinates are canvas coordinates.
  cv::namedWindow(kWindow, cv::WINDOW_NORMAL | cv::WINDOW_KEEPRATIO | cv::WINDOW_GUI_NORMAL);
  if (options.fullscreen) {
    impl_->canvas_size = go_fullscreen(options);
  } else {
    impl_->canvas_size = {options.width, options.height};
    cv::resizeWindow(kWindow, options.width, options.height);
  }
  cv::setMouseCallback(kWindow, &Impl::on_mouse, impl_.get());
  spdlog::info("study window {}x{} ({})", impl_->canvas_size.width, impl_->canvas_size.height,
               options.fullscreen ? "full screen" : "windowed");
}

WindowPresenter::~WindowPresenter() {
  try {
    cv::destroyWindow(kWindow);
    cv::waitKey(1);
  } catch (const cv::Exception&) {
  }
}

ScreenInfo WindowPresenter::screen() const {
  return {impl_->canvas_size.width, impl_->canvas_size.height, "window"};
}

ScreenReply WindowPresenter::show_screen(const PlanScreen& screen) {
  Impl& m = *impl_;
  const ScreenKind kind = screen.kind;
  const bool consent = kind == ScreenKind::consent;
  cv::Mat canvas(m.canvas_size, CV_8UC3);
  draw_text_screen(canvas, screen.title, screen.text, screen.hint, m.text);
  cv::Mat shown = canvas.clone();
  cv::imshow(kWindow, shown);
  m.snapshot(shown, std::string("screen_") + screen_kind_name(kind));
  const auto t0 = Clock::now();
  bool confirming = false;
  m.clicks.clear();
  while (true) {
    const int key = cv::waitKeyEx(30);
    if (m.window_closed()) return ScreenReply::abort;
    const bool debounced = ms_since(t0) > kDebounceMs;
    if (confirming && key != -1) {
      if (key == 'y' || key == 'Y') return ScreenReply::abort;
      confirming = false;
      cv::imshow(kWindow, canvas);
      continue;
    }
    if (!debounced) {
      m.clicks.clear();
      continue;
    }
    if (key == kEsc && kind != ScreenKind::finished) {
      confirming = true;
      shown = canvas.clone();
      draw_abort_confirmation(shown, m.text);
      cv::imshow(kWindow, shown);
      continue;
    }
    if (consent) {
      if (key == 'y' || key == 'Y') return ScreenReply::proceed;
      if (key == 'n' || key == 'N') return ScreenReply::decline;
      continue;
    }
    if (key != -1 || !m.clicks.empty()) return ScreenReply::proceed;
  }
}

TrialOutcome WindowPresenter::run_trial(const TrialRequest& req) {
  Impl& m = *impl_;
  const std::vector<StudyQuestion>& qs = *req.questions;
  const TrialLayout layout = layout_trial_screen(m.canvas_size, qs, req.video_share);
  const std::string tag = "trial_" + std::to_string(req.trial->index);
  // The inter-trial screen replaces the answered screen at once, and stays while the clip decodes
  // and at least inter_trial_min_ms.
  const Clock::time_point inter_trial_start = Clock::now();
  {
    cv::Mat blank(m.canvas_size, CV_8UC3);
    draw_inter_trial(blank, layout, req.inter_trial_screen == InterTrialScreen::fixation);
    cv::imshow(kWindow, blank);
    cv::waitKey(1);
    m.snapshot(blank, tag + "_inter_trial");
  }
  std::unique_ptr<VideoSource> clip =
      m.prefetched && m.prefetched->path() == req.video_path
          ? std::move(m.prefetched)
          : std::make_unique<VideoSource>(req.video_path, layout.video_area, req.fps, req.loop_video,
                                          m.options.decode_ahead);
  m.prefetched.reset();
  VideoSource& video = *clip;
  TrialScreenState state;
  DigitEntry digits;  // an open first digit on a 10- or 11-point scale
  state.answers.assign(qs.size(), -1);
  // Locked until the minimum viewing time has passed (and a play-once clip has ended): keys and
  // clicks before then are dropped, and the panel says so.
  state.questions_enabled = false;
  state.header = req.header;
  std::vector<Answer> answers(qs.size());

  TrialOutcome out;
  cv::Mat static_panel(m.canvas_size, CV_8UC3), panel(m.canvas_size, CV_8UC3), canvas(m.canvas_size, CV_8UC3);
  bool static_dirty = true, panel_dirty = true, redraw = true, snap_onset = true, snap_answered = true;
  const double period_ms = 1000.0 / video.fps();
  Clock::time_point onset;
  std::vector<double> handover_ms;  // when each new frame was handed to the window, ms after onset
  long shown = -1;
  bool video_done = false, onset_pending = true;
  // The static panel (FreeType text, tens of ms) is drawn before onset, so it costs no frame.
  draw_trial_static(static_panel, layout, qs, state.header, state.questions_enabled, m.text);
  static_dirty = false;
  m.wait_until(inter_trial_start +
               std::chrono::microseconds(static_cast<long>(req.inter_trial_min_ms * 1000)));
  m.clicks.clear();

  auto answer = [&](int q, int value, double rt_ms) {
    state.answers[static_cast<size_t>(q)] = value;
    answers[static_cast<size_t>(q)] = Answer{qs[static_cast<size_t>(q)].id, value, rt_ms, iso8601_utc_now()};
    panel_dirty = true;
  };

  while (true) {
    // 1. Which frame is due (steady clock), counting skipped ones as dropped.
    if (shown < 0) onset = Clock::now();
    long due = static_cast<long>(std::floor(ms_since(onset) / period_ms));
    if (!req.loop_video && due >= video.frame_count()) {
      due = video.frame_count() - 1;
      video_done = true;
    }
    if (!state.questions_enabled && !onset_pending && (req.loop_video || video_done) &&
        ms_since(onset) >= req.min_view_ms) {
      state.questions_enabled = true, static_dirty = panel_dirty = true;
      digits = {};
      // The clip has been seen: the next one opens and decodes its first frames on its own threads
      // while the participant answers (not earlier, so it takes no CPU from this clip's playback).
      if (!req.next_video_path.empty())
        m.prefetched = std::make_unique<VideoSource>(req.next_video_path, layout.video_area, req.fps,
                                                     req.loop_video, m.options.decode_ahead);
    }
    const cv::Mat* frame = nullptr;
    const bool new_frame = due != shown;
    if (new_frame) {
      if (shown >= 0 && due > shown + 1) out.timing.frames_dropped += due - shown - 1;
      frame = &video.frame(due);
      shown = due;
      ++out.timing.frames_shown;
      redraw = true;
    }
    // 2. Compose: the panel only when answers changed, the video every frame.
    if (static_dirty) {
      draw_trial_static(static_panel, layout, qs, state.header, state.questions_enabled, m.text);
      static_dirty = false;
    }
    if (panel_dirty) {
      static_panel.copyTo(panel);
      draw_trial_answers(panel, layout, qs, state, m.text);
      panel_dirty = false;
      redraw = true;
      frame = &video.frame(shown);
    }
    if (redraw) {
      if (frame != nullptr || state.confirm_abort) {
        panel.copyTo(canvas);
        draw_video_frame(canvas, layout, *(frame ? frame : &video.frame(shown)));
        if (state.confirm_abort) draw_abort_confirmation(canvas, m.text);
      }
      cv::imshow(kWindow, canvas);
      redraw = false;
      if (onset_pending) {  // the first frame is on its way: this is the stimulus onset
        onset_pending = false;
        onset = m.discard_pending_input();
        out.timing.onset_utc = iso8601_utc_now();
        out.timing.inter_trial_ms =
            std::chrono::duration<double, std::milli>(onset - inter_trial_start).count();
      }
      if (new_frame) handover_ms.push_back(ms_since(onset));
      if (snap_onset) m.snapshot(canvas, tag + "_onset"), snap_onset = false;
      if (snap_answered && state.all_answered() && !state.confirm_abort)
        m.snapshot(canvas, tag + "_answered"), snap_answered = false;
    }
    // 3. Wait for input until the next frame is due.
    const double next_due_ms = (shown + 1) * period_ms - ms_since(onset);
    const int wait_ms = video_done ? 20 : std::max(1, static_cast<int>(std::ceil(next_due_ms)));
    const int key = cv::waitKeyEx(wait_ms);
    const double now_ms = ms_since(onset);
    if (m.window_closed()) {
      spdlog::warn("the study window was closed: session stopped");
      out.aborted = true;
      return out;
    }
    if (state.confirm_abort) {
      if (key == 'y' || key == 'Y') {
        out.aborted = true;
        return out;
      }
      if (key != -1) state.confirm_abort = false, redraw = true, frame = nullptr, panel_dirty = true;
      m.clicks.clear();
      continue;
    }
    if (key == kEsc) {
      state.confirm_abort = true;
      redraw = true;
      continue;
    }
    bool next = false;
    if (!m.clicks.empty()) digits = {};
    while (!m.clicks.empty()) {
      const cv::Point p = m.clicks.front();
      m.clicks.pop_front();
      if (auto hit = hit_test(layout, state, p)) {
        if (hit->question < 0)
          next = true;
        else
          answer(hit->question, hit->value, now_ms);
      }
    }
    if (state.questions_enabled && key != -1) {
      const int d = digit_of(key);
      if (d >= 0) {
        if (const auto a = enter_digit(digits, state, qs, d)) answer(a->first, a->second, now_ms);
      } else {
        digits = {};
      }
      const int yn = state.first_unanswered(qs, QuestionKind::yesno);
      if (yn >= 0 && (key == 'y' || key == 'Y')) answer(yn, 1, now_ms);
      if (yn >= 0 && (key == 'n' || key == 'N')) answer(yn, 0, now_ms);
      if (is_enter(key)) next = true;
    }
    if (next && state.all_answered()) break;
  }
  out.answers = answers;
  out.timing.intervals = frame_interval_stats(handover_ms);
  return out;
}

}  // namespace crowdlab::study
