// The session plan (session_plan.hpp) that the native window and the web page both interpret, and the
// one participant id rule (participant_id.hpp) that `study`, the page and `import-web` apply.
#include <nlohmann/json.hpp>
#include <regex>

#include "study_ui/participant_id.hpp"
#include "study_ui/session_plan.hpp"
#include "study_ui/session_texts.hpp"
#include "study_ui/web_export.hpp"
#include "tests/study/study_fixture.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_plan {

using namespace crowdlab;
using namespace crowdlab::study;

TEST_CASE("participant ids: the page's pattern accepts exactly the ids crowdlab accepts", "[study]") {
  const std::regex page(kParticipantIdPattern, std::regex::ECMAScript);
  const std::vector<std::string> ids = {
      "P07",  "a",         "0",    "A_b-c", std::string(64, 'x'), "",    "_P07", "-P07", "P 07", "P07!",
      "P07 ", "p\xc3\xa9", ".P07", "P/07",  std::string(65, 'x'), "P\n", "7_",   "Z-"};
  for (const std::string& id : ids) {
    CAPTURE(id);
    CHECK(std::regex_match(id, page) == valid_participant_id(id));
  }
  CHECK_FALSE(valid_participant_id("_P07"));  // issue 29, finding 1: the page started the study with it
  CHECK_FALSE(valid_participant_id("-P07"));
  CHECK_THROWS_WITH(check_participant_id("-P07"), Catch::Contains("starting with a letter or digit"));
  // The page gets the rule from timeline.json, not from a copy of its own.
  const auto dir = test::scratch_dir("plan-ids");
  const auto m = test::make_stimuli(dir / "stimuli", {{"density", {"2.22"}}}, 1);
  const nlohmann::json timeline = web_timeline(test::likert_spec(), m, "sha", {"P01"});
  CHECK(timeline["participant_id"]["pattern"] == kParticipantIdPattern);
  CHECK(timeline["participant_id"]["rule"] == kParticipantIdRule);
}

TEST_CASE("session plan: screens with one hint each, trial headers, breaks, parts, resume, min view time",
          "[study]") {
  const auto dir = test::scratch_dir("plan");
  auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}}, 1);
  m.entries.back().factors["method"] = "";  // a practice trial of no block: before all blocks
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.instructions = "Watch and answer.";
  spec.protocol.consent = "Do you agree?";
  spec.protocol.break_every = 2;
  spec.protocol.block_by = "method";
  const SessionPlan plan = session_plan(spec, m, "P06");
  std::vector<std::string> seen;
  for (const PlanStep& s : plan.steps)
    seen.push_back(s.kind == StepKind::trial ? s.header : screen_kind_name(s.screen.kind));
  CHECK(seen == std::vector<std::string>{"instructions", "consent", "practice", "Practice trial 1 of 1",
                                         "block", "Trial 1 of 4", "Trial 2 of 4", "break", "block",
                                         "Trial 3 of 4", "Trial 4 of 4", "finished"});
  for (const PlanStep& s : plan.steps) {
    if (s.kind != StepKind::screen) continue;
    CAPTURE(s.screen.title);
    // The key to press is said once, in the hint line, never in the body (finding 14).
    CHECK(s.screen.text.find("Press any key") == std::string::npos);
    CHECK(s.screen.hint == (s.screen.kind == ScreenKind::consent    ? texts::kConsentHint
                            : s.screen.kind == ScreenKind::finished ? texts::kCloseHint
                                                                    : texts::kContinueHint));
  }
  CHECK(plan.steps[4].screen.title == "Part 1");
  CHECK(plan.steps[8].screen.title == "Part 2");
  // Minimum viewing time: the clip's duration by default (10 frames at 30 fps), else the spec's.
  CHECK(plan.steps[3].min_view_ms == Approx(1000.0 / 3.0));
  spec.protocol.min_view_ms = 250.0;
  CHECK(session_plan(spec, m, "P06").steps[3].min_view_ms == Approx(250.0));
  // Resume after trials 1-3: instructions, then trial 4 (the break before trial 4 is shown, the intros
  // of answered trials and the consent are not), and so on.
  const std::set<int> done = {1, 2, 3};
  std::vector<std::string> resumed;
  for (const PlanStep& s : plan.steps)
    if (!skip_on_resume(s, done))
      resumed.push_back(s.kind == StepKind::trial ? s.header : screen_kind_name(s.screen.kind));
  CHECK(resumed == std::vector<std::string>{"instructions", "break", "block", "Trial 3 of 4", "Trial 4 of 4",
                                            "finished"});
  // timeline.json carries the plan per embedded id.
  const nlohmann::json timeline = web_timeline(spec, m, "sha", {"P06"});
  REQUIRE(timeline["plans"]["P06"].size() == plan.steps.size());
  CHECK(timeline["plans"]["P06"][3]["header"] == "Practice trial 1 of 1");
  CHECK(timeline["plans"]["P06"][3]["min_view_ms"] == 250);
  CHECK(timeline["plans"]["P06"][1]["first_session_only"] == true);
  CHECK(timeline["inter_trial"]["min_ms"] == spec.protocol.inter_trial_min_ms);
}

}  // namespace test_plan
