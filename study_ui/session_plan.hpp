#pragma once
// session_plan: one participant's whole session as plain data, computed once in C++. The native
// presenter (run_session + WindowPresenter) and the web page (crowdlab_study.js, which reads it from
// timeline.json) both interpret it; neither decides the protocol on its own.
//
// Steps, in order (issue 29): instructions (when the spec has them), consent (when it has one; first
// session only), then for each trial of build_trial_list's order: the practice intro before the first
// practice trial, a part intro where a new block starts (after practice, or between blocks when there
// are several), the trial itself (its header "Trial k of N" counting test trials only, "Practice
// trial k of P" for practice, and its minimum viewing time), a break after every
// protocol.break_every-th test trial (not after the last trial); finally the end screen.
// Each screen has a title, a body and a hint line (the key that moves on). The inter-trial screen
// (protocol.inter_trial) precedes every trial step.
//
// Resume (a native --resume, a reloaded web page): a step is skipped when the trial named by its
// skip_if_done is already answered (a trial step names itself; an intro the trial it opens; a break
// the trial after it), and consent is skipped once any trial is answered (first_session_only). Both
// interpreters apply exactly this rule (skip_on_resume here, skipOnResume in the page).
//
// Minimum viewing time (protocol.min_view_ms): answers given before it are not accepted. Default
// (min_view_ms < 0 in the spec): the clip's duration (manifest duration_s, else frames / fps), i.e.
// one full loop of a looping Likert clip and the whole clip of a play-once 2AFC clip.
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "study_ui/build_trial_list.hpp"

namespace crowdlab::study {

enum class ScreenKind { instructions, consent, practice_intro, block_intro, break_screen, finished };

/// A text screen: what the participant reads.
struct PlanScreen {
  ScreenKind kind = ScreenKind::instructions;
  std::string title;
  std::string text;
  std::string hint;  ///< bottom line: which key moves on
};

enum class StepKind { screen, trial };

struct PlanStep {
  StepKind kind = StepKind::screen;
  PlanScreen screen;                ///< kind == screen
  int trial = 0;                    ///< kind == trial: Trial::index (1-based)
  std::string header;               ///< kind == trial: "Trial 3 of 40" / "Practice trial 1 of 2"
  double min_view_ms = 0.0;         ///< kind == trial: answers before onset + this are not accepted
  int skip_if_done = 0;             ///< skipped on resume when this trial is answered (0: never)
  bool first_session_only = false;  ///< consent: skipped once any trial is answered
};

struct SessionPlan {
  std::vector<Trial> trials;  ///< build_trial_list's order; trials[i].index == i + 1
  std::vector<PlanStep> steps;
};

/// "instructions", "consent", "practice", "block", "break", "finished".
const char* screen_kind_name(ScreenKind kind);

/// The plan of `participant`. Throws InputError like build_trial_list and resolve_questions.
SessionPlan session_plan(const ExperimentSpec& spec, const StimulusManifest& manifest,
                         const std::string& participant);

/// The resume rule above: true when `step` is not shown to a participant who answered `done`.
bool skip_on_resume(const PlanStep& step, const std::set<int>& done);

/// The plan's steps as timeline.json writes them: {"kind": "screen", "screen": name, "title", "text",
/// "hint", "skip_if_done", "first_session_only"} or {"kind": "trial", "trial", "stimulus", "block",
/// "block_number", "practice", "header", "min_view_ms", "skip_if_done"}.
nlohmann::json plan_steps_json(const SessionPlan& plan);

}  // namespace crowdlab::study
