#pragma once
// WindowPresenter: the participant's screen, a native window through OpenCV highgui (Qt backend on
// Debian), full screen by default, text drawn with FreeType (cv::freetype, DejaVu Sans). When the
// window system does not apply full screen (an X server without a window manager) the window covers
// the X screen itself (size from x11_screen_size); when it cannot, it falls back to a 1280x720 window
// with a warning, or fails with require_fullscreen.
//
// Between trials: the inter-trial screen (protocol.inter_trial: blank, or a fixation cross where the
// video will appear) replaces the answered screen at once and stays while the next clip decodes and
// for at least inter_trial.min_ms; the measured gap (inter-trial screen shown -> onset) is logged.
// Text screens show the plan's title, body and hint line (session_plan.hpp).
// Trial screen: the video on top, the questions below (statement left, answer scale right), a
// "Next" button bottom right that is enabled only when every question is answered.
//   - Answers: mouse click on a scale point or yes/no button; number keys (top row or keypad)
//     answer the first unanswered scale question (10- and 11-point scales: two digits for 10 and 11,
//     see scale_keys.hpp); y / n answer the yes/no question. A click may
//     change an answer within the trial (its RT is then the time of the last change); there is no
//     going back to an earlier trial. Enter or Space (or a click on Next) moves on.
//   - Esc shows "Quit the session?"; only Y confirms, any other key resumes the trial.
//   - Video: streamed by a decoder thread a few frames ahead (video_source.hpp), scaled to the video
//     area; the next trial's clip is opened and its first frames decoded while the participant
//     answers (TrialRequest::next_video_path), so the inter-trial screen lasts inter_trial.min_ms,
//     not a clip's decoding. Frames are scheduled against std::chrono::steady_clock: frame k is due
//     at onset + k / fps; when the loop falls behind, late frames are skipped so the clip keeps real
//     time, and every skipped frame is counted as dropped (logged per trial and summed in the session
//     metadata). The loop wraps from the last frame to frame 0 at the regular frame period (the
//     decoder reopens the file ahead of time), so a clip rendered to loop shows no seam.
//   - Minimum viewing time (TrialRequest::min_view_ms, from the plan): the answers are locked until
//     onset + min_view_ms (and, for a play-once clip, its end); keys and clicks before then are
//     dropped, and the Next button reads "Watch the clip".
//   - loop_video = false (seed 001 §3.1.5: questions "after each trial"): the clip plays once, and the
//     questions are enabled when it ends.
//   - Response time: from stimulus onset to each answer. Onset: the first frame has been handed to
//     the window (cv::imshow) and every key and click queued before it has been discarded, so input
//     made during the previous trial's Next or while this clip loaded never answers this trial.
// Text screens (instructions, consent, breaks) wait for a key; consent needs Y (agree) or N (decline);
// keys pressed within 300 ms of a screen appearing are ignored (no accidental skip by key repeat).
// snapshot_dir (optional): PNGs of what was drawn (trial onset, all-answered state, text screens),
// for documentation and for tests; this is the window's own rendered canvas.
#include <memory>
#include <string>

#include "study_ui/presenter.hpp"

namespace crowdlab::study {

struct WindowOptions {
  bool fullscreen = true;
  bool require_fullscreen = false;  ///< fail (RuntimeError) rather than fall back to a smaller window
  int width = 1280;                 ///< canvas size when not full screen
  int height = 720;
  std::string font_path = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  std::string snapshot_dir;
  int decode_ahead = 6;  ///< frames decoded ahead of the screen (the memory a clip costs)
};

class WindowPresenter final : public Presenter {
 public:
  /// Opens the window. Throws RuntimeError when there is no display or the font cannot be loaded.
  explicit WindowPresenter(const WindowOptions& options);
  ~WindowPresenter() override;
  WindowPresenter(const WindowPresenter&) = delete;
  WindowPresenter& operator=(const WindowPresenter&) = delete;

  ScreenInfo screen() const override;
  ScreenReply show_screen(const PlanScreen& screen) override;
  TrialOutcome run_trial(const TrialRequest& request) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace crowdlab::study
