#pragma once
// Test-only fixture: gomez2024's corridor (seed 000's non-stationary scenario) animated as `run` animates
// it, shared by the corridor tests of test_correction_quality.cpp and test_follow_root_offsets.cpp.
#include <catch2/catch.hpp>

#include "framework/animation/animate_crowd.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/pipeline/body_model.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/test_paths.hpp"

namespace crowdlab::test {

/// gomez2024's corridor at its lowest density (or its highest, 6.66 /m^2, when `densest`), `seconds`
/// long: walkers whose legs touch their neighbours'. On procedural capsule bodies (or the spec's MPFB2
/// bodies, as the experiments use, when `spec_bodies`). `length_m` > 0 shortens the corridor (the
/// spec's is 6 m) at the same densities: fewer characters.
inline CrowdAnimation corridor_walkers(double seconds, bool densest = false, bool spec_bodies = false,
                                       double length_m = 0.0) {
  ExperimentSpec spec =
      load_experiment_spec((source_dir() / "experiments/gomez2024_nonstationary.yaml").string());
  spec.duration_s = seconds;
  if (length_m > 0.0) spec.scenario.depth_m = length_m;  // the same density on a shorter corridor
  if (!spec_bodies)
    spec.animation.body_model = BodyModel::procedural;  // the bodies the thresholds were measured on
  const std::vector<Condition> conditions = enumerate_conditions(spec);
  REQUIRE(!conditions.empty());
  const Condition& condition = densest ? conditions.back() : conditions.front();
  const ScenarioResult s = generate_scenario(spec, condition);
  AnimationContext ctx;
  ctx.scenario = s.scenario;
  ctx.seed = condition.seed;
  if (spec_bodies) apply_body_model(spec.animation, s.trajectories.agents.size(), ctx);
  return animate_crowd(s.trajectories, s.environment, spec.animation, ctx);
}

}  // namespace crowdlab::test
