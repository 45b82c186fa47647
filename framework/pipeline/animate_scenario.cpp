#include "framework/pipeline/animate_scenario.hpp"

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/orient_to_surface.hpp"
#include "framework/pipeline/body_model.hpp"

namespace crowdlab {

CrowdAnimation animate_scenario(const ExperimentSpec& spec, const Condition& crowd_condition,
                                const std::string& key, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface) {
  AnimationContext ctx;
  const ConditionParams& p = crowd_condition.params;
  ctx.scenario = p.scenario;
  ctx.seed = crowd_condition.seed;
  ctx.condition_id = key;
  if (p.shoulder_count) ctx.shoulder_count = *p.shoulder_count;
  ctx.trigger_probability = p.trigger_probability;
  apply_body_model(spec.animation, scenario.trajectories.agents.size(), ctx);
  CrowdAnimation crowd = animate_crowd(scenario.trajectories, scenario.environment, spec.animation, ctx);
  // Surface crowds walk on the developed plane; stand each frame on the surface.
  if (!surface.empty()) orient_to_surface(crowd, scenario.trajectories, surface);
  crowd.meta.seed = crowd_condition.seed;
  crowd.meta.condition_id = key;
  crowd.meta.scenario = kind_name(scenario.scenario);
  return crowd;
}

}  // namespace crowdlab
