#include "experiments/cli/bench_render_scene.hpp"

#include <cmath>
#include <filesystem>

#include "crowdlab_embedded_paper_specs.hpp"
#include "framework/core/error.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/pipeline/animate_scenario.hpp"
#include "framework/pipeline/crowd_key.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli {
namespace {

ExperimentSpec load_scene_spec(const BenchRenderScene& scene) {
  if (!scene.spec_path.empty()) return load_experiment_spec(scene.spec_path);
  return load_experiment_spec_text(kSpecGomez2024Stationary, "gomez2024_stationary.yaml (embedded)",
                                   std::filesystem::current_path().string());
}

Condition pick_condition(const ExperimentSpec& spec, const BenchRenderScene& scene) {
  for (const Condition& c : enumerate_conditions(spec)) {
    if (!scene.condition_id.empty()) {
      if (c.id == scene.condition_id) return c;
      continue;
    }
    if (c.params.density_per_m2 && std::abs(*c.params.density_per_m2 - scene.density) < 1e-9) return c;
  }
  throw InputError(SourceLocation{spec.source_path, 0, 0, "--condition"},
                   scene.condition_id.empty() ? "no condition with density " + std::to_string(scene.density)
                                              : "no condition with id '" + scene.condition_id + "'");
}

}  // namespace

CrowdAnimation make_bench_render_crowd(const BenchRenderScene& scene) {
  ExperimentSpec spec = load_scene_spec(scene);
  if (scene.body_model) spec.animation.body_model = *scene.body_model;
  if (spec.animation.body_model == BodyModel::mpfb2 && spec.animation.body_model_path.empty())
    spec.animation.body_model_path = default_mpfb2_dir().string();
  if (scene.duration_s > 0.0) spec.duration_s = std::min(spec.duration_s, scene.duration_s);
  // The run pipeline's recipes, so the bench renders the crowd `crowdlab run` would make.
  const CrowdGroupRecipes recipes = crowd_group_recipes(spec, pick_condition(spec, scene));
  const ScenarioResult scenario =
      generate_scenario(recipe_spec(recipes.crowd, spec.source_path), recipe_condition(recipes.crowd));
  return animate_scenario(recipes.animation, scenario, {});
}

}  // namespace crowdlab::cli
