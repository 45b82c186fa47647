#pragma once
// Layout, drawing and hit-testing of the study window's screens, on a plain cv::Mat (no window
// needed, so it is testable headless and its output can be saved as a screenshot).
//
// Trial screen (canvas W x H, sizes relative to H so the layout scales from 720p to 4K):
//   header band (trial i of n / practice) | video area, aspect preserved, as large as the questions
//   allow | a compact question grid (up to three columns: six Likert questions take 3 x 2, filled
//   column by column so that seed 000's paired items Q1/Q2, Q3/Q4, Q5/Q6 share a column) with the
//   Next button at its right. At 1920x1080 with six questions the 16:9 video gets 1292x727.
// Each question cell: statement (wrapped, two lines) above its answer row: k numbered circles with
// the end labels under the first and last, or Yes / No buttons. Font sizes: body 2.2 % of H (23 px
// at 1080p, about 0.5 degrees of visual angle at 60 cm on a 24-inch screen).
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "study_ui/study_question.hpp"
#include "study_ui/text_renderer.hpp"

namespace crowdlab::study {

struct TrialScreenState {
  std::vector<int> answers;       ///< per question: raw answer or -1
  bool questions_enabled = true;  ///< false while a play-once clip is still running
  bool confirm_abort = false;     ///< Esc pressed: show the quit confirmation
  std::string header;             ///< e.g. "Trial 3 of 40"
  bool all_answered() const {
    for (int a : answers)
      if (a < 0) return false;
    return !answers.empty();
  }
  /// Index of the first unanswered question of `kind`, or -1.
  int first_unanswered(const std::vector<StudyQuestion>& qs, QuestionKind kind) const;
};

struct TrialLayout {
  struct Target {
    cv::Rect rect;
    int question = -1;  ///< -1: the Next button
    int value = 0;
  };
  cv::Size canvas;
  cv::Rect video_area;
  std::vector<cv::Rect> cells;  ///< one per question
  std::vector<Target> targets;
  cv::Rect next_button;
  int body_px = 19, small_px = 15;
  int header_px = 15;  ///< "Trial i of n": fixed, whatever the question cells' scale
};

/// video_share: the video's share of the canvas height (protocol.video_share); 0 = as large as the
/// questions allow. With a share the question cells scale (0.6x to 1.6x) to the space left.
TrialLayout layout_trial_screen(cv::Size canvas, const std::vector<StudyQuestion>& questions,
                                double video_share = 0.0);

/// The parts of the trial screen that do not change while the participant answers: background,
/// header, statements, unselected scales and labels (FreeType text: tens of ms, so drawn once).
void draw_trial_static(cv::Mat& canvas, const TrialLayout& layout,
                       const std::vector<StudyQuestion>& questions, const std::string& header, bool enabled,
                       const TextRenderer& text);
/// Over a static panel: the selected answers, the focus frame and the Next button (cheap).
void draw_trial_answers(cv::Mat& canvas, const TrialLayout& layout,
                        const std::vector<StudyQuestion>& questions, const TrialScreenState& state,
                        const TextRenderer& text);
/// Everything but the video (static + answers + confirmation overlay).
void draw_trial_panel(cv::Mat& canvas, const TrialLayout& layout, const std::vector<StudyQuestion>& questions,
                      const TrialScreenState& state, const TextRenderer& text);

/// Copies `frame` (BGR) into the video area, scaled to fit with its aspect ratio, letterboxed black.
void draw_video_frame(cv::Mat& canvas, const TrialLayout& layout, const cv::Mat& frame);

/// The rectangle inside `area` that a frame of `frame_size` occupies when scaled to fit.
cv::Rect fit_rect(cv::Size frame_size, cv::Rect area);

/// The target under a click, if any (a disabled Next button is not a target).
std::optional<TrialLayout::Target> hit_test(const TrialLayout& layout, const TrialScreenState& state,
                                            cv::Point p);

/// A full-canvas text screen: title, wrapped body, and a hint line at the bottom.
void draw_text_screen(cv::Mat& canvas, const std::string& title, const std::string& body,
                      const std::string& hint, const TextRenderer& text);

/// The inter-trial screen, shown while the next clip loads: the background with the video area dark,
/// and for `fixation` a light cross (5 % of the canvas height) at the video's centre, where the eyes
/// should be at onset.
void draw_inter_trial(cv::Mat& canvas, const TrialLayout& layout, bool fixation);

/// Darkens the canvas and draws the "Quit the session?" box.
void draw_abort_confirmation(cv::Mat& canvas, const TextRenderer& text);

}  // namespace crowdlab::study
