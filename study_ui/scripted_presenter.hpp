#pragma once
// ScriptedPresenter: replays answers from a CSV (`crowdlab study --responses FILE`), for headless
// pipeline tests and for re-entering paper forms.
// The file has columns stimulus,question,response and optionally rt_ms; response is 1..k, or
// yes/no/1/0 for yes/no questions. Rows are looked up by (stimulus id, question id), so the script
// does not depend on the participant's shuffled order. Every (stimulus, question) a session needs
// must be present: check() finds gaps and bad values before the session starts.
// `delay_ms` sleeps that long in every trial before answering (a slow participant; used by the
// kill-and-resume tests to have time to kill the process mid-session).
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "study_ui/presenter.hpp"

namespace crowdlab::study {

class ScriptedPresenter final : public Presenter {
 public:
  /// Reads the script; throws InputError naming file and line on a malformed row or duplicate key.
  ScriptedPresenter(const std::string& csv_path, int delay_ms);
  /// Throws InputError listing the (stimulus, question) pairs the script misses or gets wrong.
  void check(const StimulusManifest& manifest, const std::vector<StudyQuestion>& questions) const;

  ScreenInfo screen() const override { return {0, 0, "scripted"}; }
  /// Agrees to everything (consent included) and notes the screen in the transcript.
  ScreenReply show_screen(const PlanScreen& screen) override;
  TrialOutcome run_trial(const TrialRequest& request) override;
  /// What the session asked this presenter to show, in order: {"screen", "title", "text", "hint"} per
  /// text screen, {"inter_trial"} and then {"trial", "header"} per trial; the native side of the
  /// lab/online parity test (the page keeps the same transcript).
  const nlohmann::json& transcript() const { return transcript_; }

 private:
  struct Entry {
    std::string response;
    double rt_ms = -1.0;
    int line = 0;
  };
  std::string path_;
  int delay_ms_ = 0;
  std::map<std::pair<std::string, std::string>, Entry> answers_;
  nlohmann::json transcript_ = nlohmann::json::array();
  static bool parse_response(const StudyQuestion& q, const std::string& text, int& raw);
};

}  // namespace crowdlab::study
