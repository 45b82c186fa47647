#pragma once
// Presenter: everything the session engine needs from "a participant in front of a screen", so that
// the engine (run_session) has no I/O of its own. Three implementations:
//   WindowPresenter    the native full-screen window (OpenCV highgui, FreeType text)
//   ScriptedPresenter  replays answers from a CSV (--responses)
//   SimulatedPresenter answers as a simulated observer (--simulate)
#include <string>
#include <vector>

#include "study_ui/build_trial_list.hpp"
#include "study_ui/frame_interval_stats.hpp"
#include "study_ui/session_plan.hpp"
#include "study_ui/study_question.hpp"

namespace crowdlab::study {

/// How the participant left a text screen: on to the next step, quit (Esc confirmed, window closed),
/// or, on the consent screen only, declined to take part.
enum class ScreenReply { proceed, abort, decline };

/// One answer as given: the raw response and its response time from stimulus onset.
struct Answer {
  std::string question_id;
  int raw = 0;                ///< 1..k for scales, 1 = yes / 0 = no
  double rt_ms = 0.0;         ///< from stimulus onset (first frame on screen) to the answer
  std::string timestamp_utc;  ///< ISO 8601, when the answer was given
};

struct TrialRequest {
  const Trial* trial = nullptr;
  std::string video_path;  ///< absolute path of the stimulus file
  const std::vector<StudyQuestion>* questions = nullptr;
  int trial_count = 0;       ///< total trials in the session, practice included
  std::string header;        ///< from the plan: "Trial 3 of 40" (test trials only) or "Practice trial 1 of 2"
  double min_view_ms = 0.0;  ///< from the plan: answers before onset + this are not accepted
  std::string next_video_path;  ///< the clip of the trial after this one ("" = none): prefetched
  bool loop_video = true;       ///< loop until answered; otherwise play once, then ask
  double fps = 30.0;            ///< playback rate when the file does not say
  InterTrialScreen inter_trial_screen = InterTrialScreen::fixation;  ///< shown while the clip loads
  double inter_trial_min_ms = 500.0;  ///< the inter-trial screen's minimum duration
  double video_share = 0.0;           ///< video's share of the screen height; 0 = automatic
};

/// What a presenter measured of one trial's presentation (headless presenters measure nothing).
struct TrialTiming {
  std::string onset_utc;       ///< wall-clock time of the stimulus onset, ISO 8601 UTC ("" = none)
  double inter_trial_ms = -1;  ///< inter-trial screen shown -> stimulus onset (< 0: none)
  long frames_shown = 0;
  long frames_dropped = 0;
  FrameIntervalStats intervals;  ///< between consecutive frames handed to the window
};

struct TrialOutcome {
  bool aborted = false;         ///< the participant confirmed Esc: stop the session, keep what is saved
  std::vector<Answer> answers;  ///< one per question, in question order (empty when aborted)
  TrialTiming timing;
};

struct ScreenInfo {
  int width = 0;
  int height = 0;
  std::string kind;  ///< "window", "scripted", "simulated"
};

class Presenter {
 public:
  virtual ~Presenter() = default;
  virtual ScreenInfo screen() const = 0;
  /// Shows a text screen of the plan (title, body, hint line) and waits for the participant.
  virtual ScreenReply show_screen(const PlanScreen& screen) = 0;
  /// Plays the stimulus and collects one answer per question.
  virtual TrialOutcome run_trial(const TrialRequest& request) = 0;
};

/// Current UTC time as ISO 8601 with milliseconds, e.g. 2026-11-22T02:13:07.123Z.
std::string iso8601_utc_now();

}  // namespace crowdlab::study
