#include "framework/pipeline/run_experiment.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <map>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/sha256.hpp"
#include "framework/core/write_file.hpp"
#include "framework/pipeline/crowd_key.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab {
namespace fs = std::filesystem;

namespace {

/// The conditions of this run grouped by crowd, in first-appearance order of the enumeration
/// (practice conditions first), after --condition and --shard.
struct CrowdGroups {
  std::vector<std::string> order;  ///< the keys of this shard's groups
  std::map<std::string, std::vector<Condition>> conditions;
  size_t selected = 0;  ///< conditions in this shard's groups
};

/// Shards own whole crowd groups (all conditions that show one crowd), never parts of one, so no two
/// shards ever compute or write the same crowd files. Group g (in first-appearance order of the
/// enumeration) belongs to shard (g mod N) + 1: disjoint, deterministic and balanced to one group.
CrowdGroups select_groups(const ExperimentSpec& spec, const RunOptions& opt) {
  std::vector<Condition> all = enumerate_practice_conditions(spec);
  for (Condition& c : enumerate_conditions(spec)) all.push_back(std::move(c));
  std::vector<std::string> order;
  CrowdGroups groups;
  for (const Condition& c : all) {
    if (!opt.only.empty() && c.id != opt.only) continue;
    const std::string key = crowd_key(c);
    if (!groups.conditions.count(key)) order.push_back(key);
    groups.conditions[key].push_back(c);
  }
  if (!opt.only.empty() && order.empty())
    throw InputError(SourceLocation{"", 0, 0, "--condition"}, "no condition with id '" + opt.only + "'");
  for (size_t g = 0; g < order.size(); ++g)
    if (opt.shard.contains(g)) {
      groups.order.push_back(order[g]);
      groups.selected += groups.conditions[order[g]].size();
    }
  return groups;
}

void copy_spec(const ExperimentSpec& spec, const fs::path& out_dir) {
  if (spec.source_path.empty() || !fs::exists(spec.source_path)) return;
  std::ifstream in(spec.source_path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  write_file_atomic(out_dir / "spec.yaml", ss.str());
}

void link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::remove(to, ec);
  fs::create_hard_link(from, to, ec);
  if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

/// The correction-quality columns of a clip from its metrics JSON (-1 where absent).
ClipQuality clip_quality(const nlohmann::json& metrics) {
  ClipQuality q;
  if (!metrics.contains("correction_quality")) return q;
  const nlohmann::json& j = metrics.at("correction_quality");
  q.depth_p99_m = j.value("depth_p99_m", -1.0);
  q.depth_max_m = j.value("depth_max_m", -1.0);
  q.stance_foot_drift_p99_m = j.value("stance_foot_drift_p99_m", -1.0);
  q.stance_foot_drift_max_m = j.value("stance_foot_drift_max_m", -1.0);
  q.foot_pops = j.value("foot_pops", -1);
  q.foot_ground_penetration_max_m = j.value("foot_ground_penetration_max_m", -1.0);
  q.foot_ground_penetration_added_max_m = j.value("foot_ground_penetration_added_max_m", -1.0);
  q.foot_float_p99_m = j.value("foot_float_p99_m", -1.0);
  q.free_limb_dev_p99_deg = j.value("free_limb_dev_p99_deg", -1.0);
  q.free_limb_dev_max_deg = j.value("free_limb_dev_max_deg", -1.0);
  q.joint_flips = j.value("joint_flips", -1);
  q.env_penetration_p99_m = j.value("env_penetration_p99_m", -1.0);
  q.env_penetration_max_m = j.value("env_penetration_max_m", -1.0);
  q.mesh_overlap_fraction = j.value("mesh_overlap_fraction", -1.0);
  q.mesh_overlap_depth_p99_m = j.value("mesh_overlap_depth_p99_m", -1.0);
  q.proxy_coverage = j.value("proxy_coverage", -1.0);
  q.proxy_outside_p99_m = j.value("proxy_outside_p99_m", -1.0);
  return q;
}

/// Runs the presentation stages of condition `c` in table order; the stimulus stage's main output fills
/// the entry's file (relative to the run folder), size and SHA-256.
void present_condition(const ExperimentSpec& spec, const RunOptions& opt, StageRunner& runner, CrowdGroup& g,
                       const Condition& c, const fs::path& dir,
                       const std::vector<PresentationStage>& presentation, StimulusEntry& e) {
  for (const PresentationStage& p : presentation) {
    const std::optional<Stage> stage = p.make(g, c, dir);
    if (!stage) continue;
    runner.run(*stage);
    if (p.describe) p.describe(c, dir, e);
    if (!p.stimulus) continue;
    const fs::path& file = stage->outputs.front().path;
    e.file = fs::relative(file, opt.out_dir).string();
    e.width = spec.render.width;
    e.height = spec.render.height;
    e.sha256 = sha256_file_hex(file.string());
  }
}

/// One condition: its crowd (linked from the group), its metrics and its presentation.
StimulusEntry run_condition(const ExperimentSpec& spec, const RunOptions& opt, StageRunner& runner,
                            CrowdGroup& g, const Condition& c,
                            const std::vector<PresentationStage>& presentation) {
  const CrowdMethod method = c.params.method;
  const fs::path dir = opt.out_dir / "conditions" / c.id;
  fs::create_directories(dir);
  const CrowdAnimation& crowd = g.animation(method);
  link_or_copy(g.animation_path(method), dir / "crowd.glb");
  const nlohmann::json& m = spec.outputs.metrics ? g.metrics(method) : nlohmann::json::object();
  if (spec.outputs.metrics) link_or_copy(g.metrics_path(method), dir / "metrics.json");

  StimulusEntry e;
  e.id = c.id;
  for (const auto& [name, level] : c.levels) e.factors[name] = level.text;
  e.practice = c.practice;
  e.mean_overlap_l = m.value("mean_character_overlap_l", -1.0);
  e.v_i_m = m.value("volume_index_m", -1.0);
  e.collisions = m.value("collision_count", -1);
  e.quality = clip_quality(m);
  e.frames = crowd.frame_count();
  e.duration_s = crowd.duration_s();
  present_condition(spec, opt, runner, g, c, dir, presentation, e);
  return e;
}

fs::path manifest_path(const RunOptions& opt) {
  const Shard& s = opt.shard;
  return opt.out_dir / (s.count > 1 ? "manifest.shard-" + std::to_string(s.index) + "-of-" +
                                          std::to_string(s.count) + ".csv"
                                    : std::string("manifest.csv"));
}

}  // namespace

std::vector<std::string> run_stage_names(const std::vector<PresentationStage>& presentation) {
  std::vector<std::string> names;
  for (std::string_view name :
       {CrowdRecipe::kStage, AnimationRecipe::kStage, CorrectionRecipe::kStage, MetricsRecipe::kStage})
    names.emplace_back(name);
  for (const PresentationStage& p : presentation) names.push_back(p.name);
  return names;
}

RunSummary run_experiment(const ExperimentSpec& spec, const RunOptions& options,
                          const std::vector<PresentationStage>& presentation) {
  CrowdGroups groups = select_groups(spec, options);
  fs::create_directories(options.out_dir / "crowds");
  fs::create_directories(options.out_dir / "conditions");
  // What a killed run could not clean up itself (outputs half-written under a temporary name).
  if (const int stale = remove_stale_temporaries(options.out_dir))
    spdlog::info("removed {} temporary file(s) left by an interrupted run", stale);
  copy_spec(spec, options.out_dir);

  StageRunner runner(ProvenanceContext{spec.source_hash, spec.seed, options.libraries}, options.force);
  StimulusManifest manifest;
  for (const Factor& f : spec.factors) manifest.factor_names.push_back(f.name);
  Progress progress("run " + spec.name, groups.selected);
  for (const std::string& key : groups.order) {
    const std::vector<Condition>& conditions = groups.conditions[key];
    CrowdGroupRecipes recipes = crowd_group_recipes(spec, conditions.front());
    recipes.mesh_measures = options.mesh_measures;
    CrowdGroup group(std::move(recipes), runner, options.out_dir / "crowds");
    for (const Condition& c : conditions) {
      manifest.entries.push_back(run_condition(spec, options, runner, group, c, presentation));
      progress.advance();
    }
  }
  progress.finish();

  RunSummary summary;
  summary.conditions = static_cast<int>(groups.selected);
  summary.stages_run = runner.stages_run();
  summary.stages_skipped = runner.stages_skipped();
  summary.manifest = manifest_path(options);
  write_manifest(manifest, summary.manifest.string());
  return summary;
}

}  // namespace crowdlab
