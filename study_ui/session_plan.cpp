#include "study_ui/session_plan.hpp"

#include <algorithm>
#include <cmath>

#include "study_ui/session_texts.hpp"

namespace crowdlab::study {
namespace {

PlanStep screen_step(ScreenKind kind, const std::string& title, const std::string& text, int skip_if_done) {
  PlanStep s;
  s.kind = StepKind::screen;
  const char* hint = kind == ScreenKind::consent    ? texts::kConsentHint
                     : kind == ScreenKind::finished ? texts::kCloseHint
                                                    : texts::kContinueHint;
  s.screen = {kind, title, text, hint};
  s.skip_if_done = skip_if_done;
  return s;
}

/// The clip's duration in ms: manifest duration_s, else frames at the spec's frame rate, else 0.
double clip_ms(const StimulusEntry& e, double fps) {
  if (e.duration_s > 0.0) return e.duration_s * 1000.0;
  if (e.frames > 0 && fps > 0.0) return e.frames * 1000.0 / fps;
  return 0.0;
}

std::string trial_header(bool practice, int number, int count) {
  return std::string(practice ? "Practice trial " : "Trial ") + std::to_string(number) + " of " +
         std::to_string(count);
}

}  // namespace

const char* screen_kind_name(ScreenKind kind) {
  switch (kind) {
    case ScreenKind::instructions:
      return "instructions";
    case ScreenKind::consent:
      return "consent";
    case ScreenKind::practice_intro:
      return "practice";
    case ScreenKind::block_intro:
      return "block";
    case ScreenKind::break_screen:
      return "break";
    case ScreenKind::finished:
      return "finished";
  }
  return "screen";
}

SessionPlan session_plan(const ExperimentSpec& spec, const StimulusManifest& manifest,
                         const std::string& participant) {
  const ProtocolSpec& p = spec.protocol;
  SessionPlan plan;
  plan.trials = build_trial_list(p, manifest, spec.seed, participant);
  const auto& trials = plan.trials;
  const int practice_count = static_cast<int>(
      std::count_if(trials.begin(), trials.end(), [](const Trial& t) { return t.practice; }));
  const int test_count = static_cast<int>(trials.size()) - practice_count;
  const bool multiple_blocks = std::any_of(trials.begin(), trials.end(),
                                           [](const Trial& t) { return !t.practice && t.block_number > 1; });

  if (!p.instructions.empty())
    plan.steps.push_back(screen_step(ScreenKind::instructions, texts::kInstructionsTitle, p.instructions, 0));
  if (!p.consent.empty()) {
    plan.steps.push_back(screen_step(ScreenKind::consent, texts::kConsentTitle, p.consent, 0));
    plan.steps.back().first_session_only = true;
  }
  std::string current_block;
  bool in_practice = false;
  int practice_done = 0, test_done = 0;
  for (size_t i = 0; i < trials.size(); ++i) {
    const Trial& t = trials[i];
    if (t.practice && !in_practice)
      plan.steps.push_back(
          screen_step(ScreenKind::practice_intro, texts::kPracticeTitle, texts::kPracticeIntro, t.index));
    if (!t.practice && (in_practice || t.block != current_block) && (multiple_blocks || in_practice)) {
      const std::string title = multiple_blocks ? texts::kPartTitlePrefix + std::to_string(t.block_number)
                                                : std::string(texts::kMainPartTitle);
      plan.steps.push_back(screen_step(ScreenKind::block_intro, title,
                                       in_practice ? texts::kAfterPractice : texts::kBlockIntro, t.index));
    }
    in_practice = t.practice;
    current_block = t.block;
    PlanStep step;
    step.kind = StepKind::trial;
    step.trial = t.index;
    step.skip_if_done = t.index;
    step.header = t.practice ? trial_header(true, ++practice_done, practice_count)
                             : trial_header(false, ++test_done, test_count);
    step.min_view_ms = p.min_view_ms >= 0.0 ? p.min_view_ms : clip_ms(t.stimulus, spec.fps);
    plan.steps.push_back(step);
    const bool last = i + 1 == trials.size();
    if (!last && !t.practice && p.break_every > 0 && test_done % p.break_every == 0)
      plan.steps.push_back(
          screen_step(ScreenKind::break_screen, texts::kBreakTitle, p.break_text, trials[i + 1].index));
  }
  plan.steps.push_back(screen_step(ScreenKind::finished, texts::kFinishedTitle, texts::kFinished, 0));
  return plan;
}

bool skip_on_resume(const PlanStep& step, const std::set<int>& done) {
  if (step.first_session_only && !done.empty()) return true;
  return step.skip_if_done > 0 && done.count(step.skip_if_done) > 0;
}

nlohmann::json plan_steps_json(const SessionPlan& plan) {
  nlohmann::json steps = nlohmann::json::array();
  for (const PlanStep& s : plan.steps) {
    if (s.kind == StepKind::screen) {
      steps.push_back({{"kind", "screen"},
                       {"screen", screen_kind_name(s.screen.kind)},
                       {"title", s.screen.title},
                       {"text", s.screen.text},
                       {"hint", s.screen.hint},
                       {"skip_if_done", s.skip_if_done},
                       {"first_session_only", s.first_session_only}});
      continue;
    }
    const Trial& t = plan.trials[static_cast<size_t>(s.trial - 1)];
    steps.push_back({{"kind", "trial"},
                     {"trial", t.index},
                     {"stimulus", t.stimulus.id},
                     {"block", t.block},
                     {"block_number", t.block_number},
                     {"practice", t.practice},
                     {"header", s.header},
                     {"min_view_ms", std::round(s.min_view_ms)},
                     {"skip_if_done", s.skip_if_done}});
  }
  return steps;
}

}  // namespace crowdlab::study
