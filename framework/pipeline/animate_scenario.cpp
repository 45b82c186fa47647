#include "framework/pipeline/animate_scenario.hpp"

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/orient_to_surface.hpp"
#include "framework/pipeline/body_model.hpp"
#include "framework/spec/effective_scenario_type.hpp"

namespace crowdlab {

CrowdAnimation animate_scenario(const ExperimentSpec& spec, const Condition& crowd_condition,
                                const std::string& key, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface) {
  AnimationContext ctx;
  ctx.scenario_type = effective_scenario_type(spec, crowd_condition) == "manifold"
                          ? "manifold"
                          : resolve_scenario_type(spec, crowd_condition);
  ctx.seed = crowd_condition.seed;
  ctx.condition_id = key;
  if (crowd_condition.level("shoulder"))
    ctx.shoulder_count = static_cast<int>(crowd_condition.number("shoulder", 0));
  ctx.trigger_probability = crowd_condition.number("trigger", 0.0) / 100.0;
  apply_body_model(spec.animation, scenario.trajectories.agents.size(), ctx);
  CrowdAnimation crowd = animate_crowd(scenario.trajectories, scenario.environment, spec.animation, ctx);
  // Surface crowds walk on the developed plane; stand each frame on the surface.
  if (!surface.empty()) orient_to_surface(crowd, scenario.trajectories, surface);
  crowd.meta.seed = crowd_condition.seed;
  crowd.meta.condition_id = key;
  crowd.meta.scenario = scenario.scenario;
  return crowd;
}

}  // namespace crowdlab
