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

json level_json(const Condition& c) {
  json j = json::object();
  for (const auto& [name, level] : c.levels) j[name] = level.text;
  j["rep"] = c.repetition;
  return j;
}

/// Loop pre-roll of the correction when the study shows clips looping (correct_crowd.hpp), seconds.
constexpr double kLoopPrerollS = 2.0;

/// The spec's correction section as corrector parameters (0 keeps the corrector's default), with the
/// loop pre-roll when the clips are shown looping (protocol.loop_video).
CorrectorParams corrector_params(const CorrectionSpec& c, bool clips_loop) {
  CorrectorParams params;
  if (clips_loop) params.loop_preroll_s = kLoopPrerollS;
  if (c.stiffness > 0) params.stiffness = c.stiffness;
  params.damping = c.damping;
  if (c.collision_stiffness > 0) params.contact_stiffness = c.collision_stiffness;
  return params;
}

/// What the animation and correction stages share: a stage named `name` whose one output is the crowd
/// file `path`, written from `crowd` and read back into it when up to date.
Stage crowd_file_stage(const std::string& name, const fs::path& path, std::optional<CrowdAnimation>& crowd) {
  Stage s;
  s.name = name;
  s.outputs.push_back({path, [&crowd](const fs::path& tmp) { write_crowd_glb(*crowd, tmp.string()); }});
  s.load = [&crowd, path] { crowd = read_crowd_glb(path.string()); };
  return s;
}

}  // namespace

CrowdGroup::CrowdGroup(const ExperimentSpec& spec, StageRunner& runner, const fs::path& crowds_dir,
                       const Condition& first)
    : spec_(spec),
      runner_(runner),
      key_(crowd_key(first)),
      dir_(crowds_dir / key_),
      condition_(crowd_condition(spec, first)) {
  fs::create_directories(dir_);
  // The animation is computed from the crowd stage's result in memory (deterministic from the seed), so
  // its input hash covers the crowd stage's recipe; every later stage reads files and hashes them.
  crowd_hash_ = crowd_stage().input_hash();
}

bool CrowdGroup::is_manifold() const {
  return condition_.params.scenario == ScenarioKind::manifold;
}

const ScenarioResult& CrowdGroup::scenario() {
  if (scenario_) return *scenario_;
  if (is_manifold()) {
    // Crowds on surfaces come from the surface stage (seed 002), with their 3D frames.
    ManifoldScenario m = generate_manifold_scenario(spec_, condition_);
    surface_ = std::move(m.surface);
    scenario_ = std::move(m.result);
  } else {
    scenario_ = generate_scenario(spec_, condition_);
  }
  return *scenario_;
}

const SurfaceTrajectories& CrowdGroup::surface() {
  scenario();
  return surface_;
}

Stage CrowdGroup::crowd_stage() {
  Stage s;
  s.name = "crowd";
  s.params["levels"] = level_json(condition_);
  s.params["scenario"] = kind_name(spec_.scenario.type);
  s.params["seed"] = condition_.seed;
  s.params["spec"] = spec_.source_hash;  // scenario/crowd sections live in the spec text
  s.outputs.push_back({dir_ / "trajectories.csv", [this](const fs::path& tmp) {
                         write_text_file(tmp, trajectories_csv(scenario().trajectories));
                       }});
  if (is_manifold())
    s.outputs.push_back({dir_ / "surface_trajectories.csv", [this](const fs::path& tmp) {
                           write_text_file(tmp, surface_trajectories_csv(surface(), spec_.fps));
                         }});
  return s;
}

Stage CrowdGroup::animation_stage() {
  const size_t i = index_of(CrowdMethod::baseline);
  Stage s = crowd_file_stage("animation", animation_path(CrowdMethod::baseline), animation_[i]);
  // The MPFB2 asset folder may come from the environment, so it is an input of its own.
  s.params = json{{"spec", spec_.source_hash}, {"body_model_path", spec_.animation.body_model_path}};
  s.upstream = {crowd_hash_};
  s.compute = [this, i] {
    const ScenarioResult& crowd = scenario();
    animation_[i] = animate_scenario(spec_, condition_, key_, crowd, surface());
  };
  return s;
}

Stage CrowdGroup::correction_stage() {
  const size_t i = index_of(CrowdMethod::corrected);
  Stage s = crowd_file_stage("correction", animation_path(CrowdMethod::corrected), animation_[i]);
  s.params = json{{"damping", spec_.correction.damping},
                  {"stiffness", spec_.correction.stiffness},
                  {"contact_stiffness", spec_.correction.collision_stiffness},
                  {"loop_preroll_s", spec_.protocol.loop_video ? kLoopPrerollS : 0.0}};
  s.inputs = {animation_path(CrowdMethod::baseline)};
  s.compute = [this, i] {
    const CrowdAnimation& input = animation(CrowdMethod::baseline);
    Progress progress("correct " + key_, static_cast<size_t>(input.frame_count()));
    CorrectionReport report;
    animation_[i] = correct_crowd(input, corrector_params(spec_.correction, spec_.protocol.loop_video),
                                  &progress, &report);
    if (report.rejected_steps > 0)
      spdlog::warn("{}: the corrector rejected {} of {} steps and kept the last stable state", key_,
                   report.rejected_steps, report.frames);
  };
  return s;
}

Stage CrowdGroup::metrics_stage(CrowdMethod method) {
  const size_t i = index_of(method);
  const fs::path out = metrics_path(method);
  Stage s;
  s.name = "metrics";
  // The correction-quality measures compare the animation with its input, the baseline (for the
  // baseline itself: the same animation, so drift and pops read 0 and depth and the feet's ground
  // penetration are its own).
  s.params = json{{"correction_quality_input", kind_name(CrowdMethod::baseline)}};
  s.inputs = {animation_path(method)};
  if (method != CrowdMethod::baseline) s.inputs.push_back(animation_path(CrowdMethod::baseline));
  s.outputs.push_back(
      {out, [this, i](const fs::path& tmp) { write_text_file(tmp, metrics_[i]->dump(2) + "\n"); }});
  s.compute = [this, i, method] {
    const CrowdAnimation& crowd = animation(method);
    json m = crowd_metrics_json(measure_crowd(crowd), false);
    json q = correction_quality_json(measure_correction_quality(animation(CrowdMethod::baseline), crowd));
    if (is_manifold()) {  // the feet's ground is the surface there, not y = 0
      q.erase("foot_ground_penetration_max_m");
      q.erase("foot_ground_penetration_p99_m");
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
