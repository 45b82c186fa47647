// The one estimator of a spec's work (framework/spec/estimate_work.hpp, issue 33 item 3): the loader,
// the 2D crowd generators and the manifold crowd ask it, so they count and refuse the same crowds.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/spec/estimate_work.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/spec/work_limits.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_estimate_work {

using namespace crowdlab;

namespace {

const std::string kSpec =
    "crowdlab: 1\nname: t\nseed: 5\n"
    "protocol:\n  type: likert\n  scale: {points: 6, labels: [a, b]}\n  questions: [{id: Q1, text: x}]\n"
    "  practice: {density: [1]}\n"
    "outputs: {video: false, contact_sheet: false}\n"
    "duration_s: 2\nfps: 10\nrepetitions: 2\n";

}  // namespace

TEST_CASE("spec: the work estimate counts conditions, practice, the largest crowd and frames") {
  const ExperimentSpec spec =
      load_experiment_spec_text(kSpec +
                                    "scenario: {type: stationary, area: {width_m: 10, depth_m: 5}}\n"
                                    "factors: {density: [1, 2.5], method: [baseline, ours]}\n",
                                "t.yaml", ".");
  const SpecWork w = estimate_spec_work(spec);
  CHECK(w.conditions == 8);           // 2 x 2 levels x 2 repetitions
  CHECK(w.practice_conditions == 1);  // one practice level
  CHECK(w.largest_crowd == 125);      // 2.5 per m^2 on 50 m^2
  CHECK(w.frames == 20);
  CHECK(largest_crowd_on_area(spec, 1000) == 2500);  // a manifold's mesh area: the same levels
  // A flow reads density as its lattice spacing: 1/sqrt(4) = 0.5 m on 10 x 10 m, two groups.
  const ExperimentSpec flow = load_experiment_spec_text(
      kSpec + "scenario: {type: flow_b, area: {width_m: 10, depth_m: 10}}\nfactors: {density: [1, 4]}\n",
      "t.yaml", ".");
  CHECK(estimate_spec_work(flow).largest_crowd == 2 * 10 * 20);
}

TEST_CASE("spec: one crowd limit, with the estimate, the limit and what to change") {
  CHECK_FALSE(crowd_limit_problem("c", kMaxCharactersPerCrowd, 1, "fix", "fix frames").has_value());
  const auto many = crowd_limit_problem("the largest crowd", 20000, 1, "lower the density", "shorten");
  REQUIRE(many);
  CHECK_THAT(*many, Catch::Contains("the largest crowd has 20000 characters, more than the limit of 10000") &&
                        Catch::Contains("lower the density"));
  const auto long_clip = crowd_limit_problem("c", 1000, 3000, "lower the density", "shorten the clip");
  REQUIRE(long_clip);
  CHECK_THAT(
      *long_clip,
      Catch::Contains("1000 characters x 3000 frames") &&
          Catch::Contains("3000000 character-frames, more than the limit of 2000000; shorten the clip"));
  CHECK_FALSE(report_limit_problem(100, 6, 600, "--x").has_value());
  const auto report = report_limit_problem(101, 6, 600, "--x");
  REQUIRE(report);
  CHECK_THAT(*report, Catch::Contains("101 participants x 6 Likert items") && Catch::Contains("606") &&
                          Catch::Contains("limit of 600") && Catch::Contains("--x"));
}

TEST_CASE("spec: the crowd generator refuses a density's character-frames as the loader does") {
  // Before the one estimator, scenario_character_count checked the character count only: a crowd within
  // 10,000 characters but over the character-frame limit (a spec changed after loading, or a caller that
  // did not load it) was generated in full.
  ExperimentSpec spec = load_experiment_spec_text(
      kSpec + "scenario: {type: stationary, area: {width_m: 30, depth_m: 30}}\nfactors: {density: [1, 5]}\n",
      "t.yaml", ".");
  const Condition condition = enumerate_conditions(spec).back();  // density 5
  CHECK(scenario_character_count(spec, condition, 900) == 4500);
  spec.duration_s = 60;  // 4500 characters x 600 frames = 2.7e6 character-frames
  CHECK_THROWS_WITH(scenario_character_count(spec, condition, 900),
                    Catch::Contains("4500 characters x 600 frames") && Catch::Contains("limit of 2000000"));
}

}  // namespace test_estimate_work
