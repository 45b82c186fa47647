#include "framework/pipeline/animate_scenario.hpp"

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/orient_to_surface.hpp"
#include "framework/pipeline/body_model.hpp"

namespace crowdlab {

CrowdAnimation animate_scenario(const AnimationRecipe& recipe, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface) {
  AnimationContext ctx;
  ctx.scenario = recipe.scenario;
  ctx.seed = recipe.seed;
  ctx.condition_id = recipe.key;
  if (recipe.shoulder_count) ctx.shoulder_count = *recipe.shoulder_count;
  ctx.trigger_probability = recipe.trigger_probability;
  apply_body_model(recipe.animation, scenario.trajectories.agents.size(), ctx);
  CrowdAnimation crowd = animate_crowd(scenario.trajectories, scenario.environment, recipe.animation, ctx);
  // Surface crowds walk on the developed plane; stand each frame on the surface.
  if (!surface.empty()) orient_to_surface(crowd, scenario.trajectories, surface);
  // The capsules the correction separates and the metrics measure (resolved by crowd_group_recipes), fitted
  // once the motion is made: the poses never read them, so only the shapes differ.
  fit_crowd_proxies(crowd, proxy_fit(recipe.animation.collision_proxies));
  crowd.meta.seed = recipe.seed;
  crowd.meta.condition_id = recipe.key;
  crowd.meta.scenario = kind_name(scenario.scenario);
  return crowd;
}

}  // namespace crowdlab
