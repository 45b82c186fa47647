#include "framework/pipeline/crowd_group.hpp"

#include <spdlog/spdlog.h>

#include <fstream>

#include "framework/core/progress.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/pipeline/animate_scenario.hpp"
#include "framework/pipeline/crowd_key.hpp"
#include "framework/pipeline/metrics_json.hpp"
#include "framework/surface/generate_manifold_scenario.hpp"

namespace crowdlab {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

/// The spec's correction section as corrector parameters (0 keeps the corrector's default), with the
/// loop pre-roll, the root following (correct_crowd.hpp) and the feet on the input's ground of the recipe.
CorrectorParams corrector_params(const CorrectionRecipe& recipe) {
  const CorrectionSpec& c = recipe.correction;
  CorrectorParams params;
  params.loop_preroll_s = recipe.loop_preroll_s;
  if (recipe.walking) walking_correction(params);
  if (c.stiffness > 0) params.stiffness = c.stiffness;
  params.damping = c.damping;
  if (c.collision_stiffness > 0) params.contact_stiffness = c.collision_stiffness;
  return params;
}

/// What the animation and correction stages share: the stage of `recipe` whose one output is the crowd
/// file `path`, written from `crowd` and read back into it when up to date.
template <class Recipe>
Stage crowd_file_stage(const Recipe& recipe, const fs::path& path, std::optional<CrowdAnimation>& crowd) {
  Stage s = stage_for(recipe);
  s.outputs.push_back({path, [&crowd](const fs::path& tmp) { write_crowd_glb(*crowd, tmp.string()); }});
  s.load = [&crowd, path] { crowd = read_crowd_glb(path.string()); };
  return s;
}

}  // namespace

CrowdGroup::CrowdGroup(CrowdGroupRecipes recipes, StageRunner& runner, const fs::path& crowds_dir)
    : recipes_(std::move(recipes)), runner_(runner), key_(recipes_.animation.key), dir_(crowds_dir / key_) {
  fs::create_directories(dir_);
  // The animation is computed from the crowd stage's result in memory (deterministic from the seed), so
  // its input hash covers the crowd stage's recipe; every later stage reads files and hashes them.
  crowd_hash_ = crowd_stage().input_hash();
}

bool CrowdGroup::is_manifold() const {
  return recipes_.crowd.params.scenario == ScenarioKind::manifold;
}

const ScenarioResult& CrowdGroup::scenario() {
  if (scenario_) return *scenario_;
  // The generators see the recipe's values only (recipe_spec()).
  const ExperimentSpec spec = recipe_spec(recipes_.crowd, recipes_.source_path);
  const Condition condition = recipe_condition(recipes_.crowd);
  if (is_manifold()) {
    // Crowds on surfaces come from the surface stage (seed 002), with their 3D frames.
    ManifoldScenario m = generate_manifold_scenario(spec, condition);
    surface_ = std::move(m.surface);
    scenario_ = std::move(m.result);
  } else {
    scenario_ = generate_scenario(spec, condition);
  }
  return *scenario_;
}

const SurfaceTrajectories& CrowdGroup::surface() {
  scenario();
  return surface_;
}

Stage CrowdGroup::crowd_stage() {
  Stage s = stage_for(recipes_.crowd);
  s.inputs = recipes_.crowd_files;
  s.outputs.push_back({dir_ / "trajectories.csv", [this](const fs::path& tmp) {
                         write_text_file(tmp, trajectories_csv(scenario().trajectories));
                       }});
  if (is_manifold())
    s.outputs.push_back({dir_ / "surface_trajectories.csv", [this](const fs::path& tmp) {
                           write_text_file(tmp, surface_trajectories_csv(surface(), recipes_.crowd.fps));
                         }});
  return s;
}

Stage CrowdGroup::animation_stage() {
  const size_t i = index_of(CrowdMethod::baseline);
  Stage s = crowd_file_stage(recipes_.animation, animation_path(CrowdMethod::baseline), animation_[i]);
  s.upstream = {crowd_hash_};
  s.inputs = recipes_.animation_files;
  s.compute = [this, i] {
    const ScenarioResult& crowd = scenario();
    animation_[i] = animate_scenario(recipes_.animation, crowd, surface());
  };
  return s;
}

Stage CrowdGroup::correction_stage() {
  const size_t i = index_of(CrowdMethod::corrected);
  Stage s = crowd_file_stage(recipes_.correction, animation_path(CrowdMethod::corrected), animation_[i]);
  s.inputs = {animation_path(CrowdMethod::baseline)};
  s.compute = [this, i] {
    const CrowdAnimation& input = animation(CrowdMethod::baseline);
    const CorrectorParams params = corrector_params(recipes_.correction);
    Progress progress("correct " + key_, correction_steps(input, params));
    CorrectionReport report;
    animation_[i] = correct_crowd(input, params, &progress, &report);
    if (report.rejected_steps > 0)
      spdlog::warn("{}: the corrector rejected {} of {} steps and kept the last stable state", key_,
                   report.rejected_steps, report.frames);
  };
  return s;
}

Stage CrowdGroup::metrics_stage(CrowdMethod method) {
  const size_t i = index_of(method);
  const fs::path out = metrics_path(method);
  // The correction-quality measures compare the animation with its input, the baseline (for the
  // baseline itself: the same animation, so drift and pops read 0 and depth and the feet's ground
  // penetration are its own).
  const MetricsRecipe recipe = metrics_recipe(recipes_, method);
  Stage s = stage_for(recipe);
  s.inputs = {animation_path(method)};
  if (method != CrowdMethod::baseline) s.inputs.push_back(animation_path(CrowdMethod::baseline));
  s.outputs.push_back(
      {out, [this, i](const fs::path& tmp) { write_text_file(tmp, metrics_[i]->dump(2) + "\n"); }});
  s.compute = [this, i, recipe] {
    const CrowdAnimation& crowd = animation(recipe.method);
    json m = crowd_metrics_json(measure_crowd(crowd), false);
    json q = correction_quality_json(measure_correction_quality(animation(CrowdMethod::baseline), crowd, 0, 1,
                                                                recipe.mesh_measures, recipe.looped));
    if (recipe.surface_ground) {  // the feet's ground is the surface there, not y = 0
      q.erase("foot_ground_penetration_max_m");
      q.erase("foot_ground_penetration_p99_m");
      q.erase("foot_ground_penetration_added_max_m");
      q.erase("foot_ground_penetration_added_p99_m");
    }
    m["correction_quality"] = std::move(q);
    metrics_[i] = std::move(m);
  };
  s.load = [this, i, out] {
    std::ifstream in(out);
    metrics_[i] = json::parse(in);
  };
  return s;
}

void CrowdGroup::run_crowd_stage() {
  if (crowd_done_) return;
  runner_.run(crowd_stage());
  crowd_done_ = true;
}

const CrowdAnimation& CrowdGroup::animation(CrowdMethod method) {
  const size_t i = index_of(method);
  if (animation_[i]) return *animation_[i];
  if (method == CrowdMethod::baseline) {
    run_crowd_stage();
    runner_.run(animation_stage());
  } else {
    animation(CrowdMethod::baseline);
    runner_.run(correction_stage());
  }
  return *animation_[i];
}

std::vector<fs::path> CrowdGroup::crowd_paths() const {
  std::vector<fs::path> paths{dir_ / "trajectories.csv"};
  if (is_manifold()) paths.push_back(dir_ / "surface_trajectories.csv");
  return paths;
}

fs::path CrowdGroup::animation_path(CrowdMethod method) const {
  return dir_ / (std::string(kind_name(method)) + ".glb");
}

const json& CrowdGroup::metrics(CrowdMethod method) {
  const size_t i = index_of(method);
  if (metrics_[i]) return *metrics_[i];
  animation(method);  // the stage reads the animation's file: make it first
  runner_.run(metrics_stage(method));
  return *metrics_[i];
}

fs::path CrowdGroup::metrics_path(CrowdMethod method) const {
  return dir_ / (std::string(kind_name(method)) + ".metrics.json");
}

}  // namespace crowdlab
