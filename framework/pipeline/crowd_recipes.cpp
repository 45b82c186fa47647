#include "framework/pipeline/crowd_recipes.hpp"

#include <algorithm>

#include "framework/pipeline/body_model.hpp"
#include "framework/pipeline/crowd_key.hpp"

namespace crowdlab {
namespace {

// What each scenario kind's generator reads (framework/crowd/generate_*_scenario.cpp,
// framework/surface/generate_manifold_scenario.cpp); every other field stays at its default in the recipe,
// so that editing it redoes no crowd of that kind (issue 30). tests/pipeline/test_stage_recipes.cpp checks
// both ways: an edit the recipe ignores leaves the generator's output unchanged.
bool simulates(ScenarioKind k) {  // a navigation model moves the crowd (corridor, flows)
  return k == ScenarioKind::corridor || k == ScenarioKind::flow_a || k == ScenarioKind::flow_b;
}

ScenarioSpec scenario_read(const ScenarioSpec& sc, const ConditionParams& p) {
  const ScenarioKind k = p.scenario;
  ScenarioSpec r;
  if (k != ScenarioKind::manifold) {
    r.width_m = sc.width_m;
    r.depth_m = sc.depth_m;
  }
  if (k == ScenarioKind::stationary) r.stage_direction_deg = sc.stage_direction_deg;
  if (k != ScenarioKind::stationary) r.walk_speed_mps = sc.walk_speed_mps;
  const bool flow = k == ScenarioKind::flow_a || k == ScenarioKind::flow_b;
  if (flow && !p.density_per_m2) r.initial_spacing_m = sc.initial_spacing_m;
  if (k == ScenarioKind::manifold) r.mesh = sc.mesh;
  // scenario_character_count reads agents only without a size factor; the flows read it always.
  const bool sized = p.characters || p.density_per_m2;
  if (flow || (k != ScenarioKind::pair_crossing && !sized)) r.agents = sc.agents;
  // passing_side is read through p.side (type_condition resolves `alternate`).
  return r;
}

CrowdSpec crowd_read(const CrowdSpec& c, ScenarioKind k) {
  CrowdSpec r;
  r.agent_radius_m = c.agent_radius_m;
  if (k == ScenarioKind::stationary || k == ScenarioKind::corridor) r.personal_space_m = c.personal_space_m;
  if (k == ScenarioKind::manifold) {  // the surface crowd (params_from_spec)
    r.model = c.model;
    r.neighbor_distance_m = c.neighbor_distance_m;
    r.max_neighbors = c.max_neighbors;
    r.time_horizon_s = c.time_horizon_s;
    r.max_speed_mps = c.max_speed_mps;
    r.dt_s = c.dt_s;
  }
  if (!simulates(k)) return r;
  // The simulation (CrowdSimulation) and make_navigation_model's fields of c.model.
  r.model = c.model;
  r.max_speed_mps = c.max_speed_mps;
  r.dt_s = c.dt_s;
  r.neighbor_distance_m = c.neighbor_distance_m;
  if (c.model == CrowdModel::orca || c.model == CrowdModel::cost) r.max_neighbors = c.max_neighbors;
  if (c.model == CrowdModel::orca) {
    r.time_horizon_s = c.time_horizon_s;
    r.obstacle_time_horizon_s = c.obstacle_time_horizon_s;
    r.overlap_free = c.overlap_free;
  }
  if (c.model == CrowdModel::cost) r.cost_weights = c.cost_weights;
  return r;
}

/// The condition's levels the crowd generators read: the scenario kind, the crowd's size, and the pair's
/// distance and side. The presentation factors (viewpoint, method) and the animation's (shoulder,
/// trigger) stay at their defaults, so every condition showing this crowd shares its recipe (crowd_key.hpp).
ConditionParams params_read(const ConditionParams& p) {
  ConditionParams r;
  r.scenario = p.scenario;
  r.density_per_m2 = p.density_per_m2;
  r.characters = p.characters;
  if (p.scenario == ScenarioKind::pair_crossing) {
    r.distance_m = p.distance_m;
    r.side = p.side;
  }
  return r;
}

}  // namespace

CrowdGroupRecipes crowd_group_recipes(const ExperimentSpec& spec, const Condition& first) {
  const Condition group = crowd_condition(spec, first);
  const ConditionParams& p = group.params;
  CrowdGroupRecipes r;
  r.source_path = spec.source_path;

  r.crowd.scenario = scenario_read(spec.scenario, p);
  r.crowd.crowd = crowd_read(spec.crowd, p.scenario);
  r.crowd.duration_s = spec.duration_s;
  r.crowd.fps = spec.fps;
  r.crowd.params = params_read(p);
  r.crowd.seed = group.seed;
  // A mesh file (the loader resolved it) is read by its content; a scene name is code.
  if (p.scenario == ScenarioKind::manifold && std::filesystem::is_regular_file(spec.scenario.mesh))
    r.crowd_files.push_back(spec.scenario.mesh);

  r.animation.animation = spec.animation;
  if (spec.animation.body_model != BodyModel::mpfb2) r.animation.animation.body_model_path.clear();
  r.animation.scenario = p.scenario;
  r.animation.animation.collision_proxies = resolve_collision_proxies(spec.animation, p.scenario);
  r.animation.shoulder_count = p.shoulder_count;
  r.animation.trigger_probability = p.trigger_probability;
  r.animation.seed = group.seed;
  r.animation.key = crowd_key(first);
  if (spec.animation.motion == MotionSource::clips) {
    for (const std::string& f : spec.animation.walk_clips) r.animation_files.push_back(f);
    for (const std::string& f : spec.animation.dance_clips) r.animation_files.push_back(f);
  }

  r.correction.correction = spec.correction;
  // The loop pre-roll (correct_crowd.hpp) for clips shown looping. Its closure keeps planted feet on
  // their anchors (blend_keeping_planted_feet.hpp); a crowd whose input does not loop (walking) gets none
  // whatever is asked (correct_crowd.cpp, input_loops).
  r.correction.loop_preroll_s = spec.protocol.loop_video ? loop_preroll_window_s(spec.duration_s) : 0.0;
  r.correction.walking = walks_on_flat_ground(p.scenario);
  r.clips_loop = spec.protocol.loop_video;
  return r;
}

bool walks_on_flat_ground(ScenarioKind scenario) {
  return scenario != ScenarioKind::stationary && scenario != ScenarioKind::manifold;
}

void walking_correction(CorrectorParams& params) {
  params.follow_root_smoothing_s = kWalkingFollowRootS;
  params.held_feet_at_input_height = true;
  params.feet_above_input_ground = true;
}

double loop_preroll_window_s(double duration_s) {
  return duration_s >= kLoopPrerollMinClipS ? std::min(kLoopPrerollS, 0.5 * duration_s) : 0.0;
}

MetricsRecipe metrics_recipe(const CrowdGroupRecipes& group, CrowdMethod method) {
  MetricsRecipe m;
  m.method = method;
  m.surface_ground = group.crowd.params.scenario == ScenarioKind::manifold;
  m.mesh_measures = group.mesh_measures;
  m.looped = group.clips_loop;
  return m;
}

ExperimentSpec recipe_spec(const CrowdRecipe& recipe, const std::string& source_path) {
  ExperimentSpec spec;
  spec.source_path = source_path;
  spec.scenario = recipe.scenario;
  spec.crowd = recipe.crowd;
  spec.duration_s = recipe.duration_s;
  spec.fps = recipe.fps;
  return spec;
}

Condition recipe_condition(const CrowdRecipe& recipe) {
  Condition c;
  c.params = recipe.params;
  c.seed = recipe.seed;
  return c;
}

}  // namespace crowdlab
