// crowd.overlap_free: from YAML (with file:line:key errors) through make_navigation_model into a
// generated scenario, where no two discs overlap by more than 1 mm while plain ORCA's do.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "framework/core/error.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/crowd/make_navigation_model.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_overlap_free_spec {

using namespace crowdlab;

namespace {

const std::string kHeader = "crowdlab: 1\nname: t\nseed: 5\n";

std::string errors_of(const std::string& yaml) {
  try {
    load_experiment_spec_text(yaml, "t.yaml", ".");
  } catch (const SpecError& e) {
    std::string all;
    for (const std::string& m : e.messages()) all += m + "\n";
    return all;
  }
  return {};
}

/// Deepest overlap r_i + r_j - |p_i - p_j| over every frame and pair (m; negative when apart).
double deepest_overlap(const CrowdTrajectories& t) {
  double worst = -1e9;
  for (int f = 0; f < t.frame_count(); ++f)
    for (std::size_t i = 0; i < t.agents.size(); ++i)
      for (std::size_t j = i + 1; j < t.agents.size(); ++j) {
        const AgentTrajectory &a = t.agents[i], &b = t.agents[j];
        const auto fi = static_cast<std::size_t>(f);
        worst = std::max(worst, a.radius_m + b.radius_m - (a.position_m[fi] - b.position_m[fi]).norm());
      }
  return worst;
}

}  // namespace

TEST_CASE("crowd.overlap_free: loaded from YAML, off by default, checked with file:line:key",
          "[crowd][spec][overlap_free]") {
  CHECK_FALSE(load_experiment_spec_text(kHeader, "t.yaml", ".").crowd.overlap_free);
  CHECK(
      load_experiment_spec_text(kHeader + "crowd: {overlap_free: true}\n", "t.yaml", ".").crowd.overlap_free);
  CHECK_FALSE(load_experiment_spec_text(kHeader + "crowd:\n  overlap_free: false\n", "t.yaml", ".")
                  .crowd.overlap_free);
  CHECK_THAT(errors_of(kHeader + "crowd:\n  overlap_free: 3\n"),
             Catch::Contains("t.yaml:5:17: crowd.overlap_free: expected true or false"));
  CHECK_THAT(
      errors_of(kHeader + "crowd:\n  model: social\n  overlap_free: true\n"),
      Catch::Contains("t.yaml:6:17: crowd.overlap_free: applies to model orca only (model is 'social')"));
  CHECK_THAT(errors_of(kHeader + "crowd: {overlap_fre: true}\n"),
             Catch::Contains("did you mean 'overlap_free'?"));
}

TEST_CASE("crowd.overlap_free reaches the ORCA model, other models reject it",
          "[crowd][spec][overlap_free]") {
  CrowdSpec c;
  CHECK_FALSE(make_navigation_model(c)->resolves_overlaps());
  c.overlap_free = true;
  CHECK(make_navigation_model(c)->resolves_overlaps());
  c.model = CrowdModel::cost;
  CHECK_THROWS_WITH(make_navigation_model(c),
                    Catch::Contains("crowd.overlap_free: applies to model orca only"));
}

TEST_CASE("crowd.overlap_free: a dense bidirectional flow from a spec keeps every disc pair apart",
          "[crowd][spec][overlap_free]") {
  // Flow B at 0.6 m initial spacing (2.8 per m^2, seed 001 experiment 2): the two blocks meet head-on.
  // fps = 1 / dt, so every frame is a simulation step (no interpolation between steps).
  const std::string yaml =
      kHeader +
      "scenario: {type: flow_b, initial_spacing_m: 0.6, area: {width_m: 3, depth_m: 3}}\n"
      "duration_s: " +
      std::string(test::kSanitized ? "3" : "6") + "\nfps: 10\n";
  double worst[2] = {0.0, 0.0};
  for (int on = 0; on < 2; ++on) {
    const ExperimentSpec spec =
        load_experiment_spec_text(yaml + (on ? "crowd: {overlap_free: true}\n" : ""), "t.yaml", ".");
    const ScenarioResult r = generate_scenario(spec, enumerate_conditions(spec).front());
    REQUIRE(r.trajectories.agents.size() >= 20);
    worst[on] = deepest_overlap(r.trajectories);
  }
  INFO("deepest overlap: plain ORCA " << worst[0] << " m, overlap-free " << worst[1] << " m");
  CHECK(worst[1] <= 1e-3);
  if (!test::kSanitized) CHECK(worst[0] > 1e-3);  // the jam the mode exists for (plain ORCA, Sec. 5.2)
}

}  // namespace test_overlap_free_spec
