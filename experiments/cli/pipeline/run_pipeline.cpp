#include "experiments/cli/pipeline/run_pipeline.hpp"

#include <spdlog/spdlog.h>

#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>

#include "experiments/cli/metrics_json.hpp"
#include "experiments/cli/pipeline/body_model.hpp"
#include "experiments/cli/pipeline/provenance.hpp"
#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/orient_to_surface.hpp"
#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/seed.hpp"
#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/spec/effective_scenario_type.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/surface/generate_manifold_scenario.hpp"
#include "stimuli/clip_sidecar.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/render_clip.hpp"
#include "stimuli/renderer.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;
using nlohmann::json;
using stimuli::parse_hex_colour;
using stimuli::render_clip;
using stimuli::Renderer;
using stimuli::RenderOptions;
using stimuli::write_contact_sheet;

namespace {

/// Factors that change how a crowd is shown, not the crowd itself.
bool is_presentation_factor(const std::string& name) {
  return name == "viewpoint" || name == "method";
}

json level_json(const Condition& c) {
  json j = json::object();
  for (const auto& [name, level] : c.levels) j[name] = level.text;
  j["rep"] = c.repetition;
  return j;
}

/// The work shared by every condition with one crowd key, computed lazily and kept in memory while
/// the group's conditions run.
struct CrowdGroup {
  std::string key;
  fs::path dir;
  Condition crowd_condition;  ///< the first condition of the group, with the crowd seed
  std::string crowd_hash, baseline_hash, ours_hash;
  std::optional<ScenarioResult> scenario;
  SurfaceTrajectories surface;  ///< manifold scenarios only: the 3D frames of the trajectories
  std::optional<CrowdAnimation> baseline, ours;
  std::map<std::string, json> metrics;         ///< method -> metrics json
  std::optional<stimuli::CrowdExtent> extent;  ///< the framing both methods share
};

/// Version of the framing rule; part of the render hashes, so clips framed by an older rule re-render.
constexpr const char* kFramingRule = "shared-extent/1";

class Runner {
 public:
  Runner(const ExperimentSpec& spec, const RunOptions& options) : spec_(spec), opt_(options) {
    context_.spec_hash = spec.source_hash;
    context_.seed = spec.seed;
  }

  RunSummary run() {
    std::vector<Condition> conditions = enumerate_practice_conditions(spec_);
    for (Condition& c : enumerate_conditions(spec_)) conditions.push_back(std::move(c));
    // Shards own whole crowd groups (all conditions that show one crowd), never parts of one, so no
    // two shards ever compute or write the same crowd files. Group g (in first-appearance order of the
    // enumeration) belongs to shard (g mod N) + 1: disjoint, deterministic and balanced to one group.
    std::vector<std::string> order;
    std::map<std::string, std::vector<Condition>> groups;
    for (const Condition& c : conditions) {
      if (!opt_.only.empty() && c.id != opt_.only) continue;
      const std::string key = crowd_key(c);
      if (!groups.count(key)) order.push_back(key);
      groups[key].push_back(c);
    }
    if (!opt_.only.empty() && order.empty())
      throw InputError(SourceLocation{"", 0, 0, "--condition"}, "no condition with id '" + opt_.only + "'");
    std::vector<std::string> mine;
    size_t selected = 0;
    for (size_t g = 0; g < order.size(); ++g)
      if (opt_.shard.contains(g)) {
        mine.push_back(order[g]);
        selected += groups[order[g]].size();
      }
    fs::create_directories(opt_.out_dir / "crowds");
    fs::create_directories(opt_.out_dir / "conditions");
    copy_spec();

    StimulusManifest manifest;
    for (const Factor& f : spec_.factors) manifest.factor_names.push_back(f.name);
    Progress progress("run " + spec_.name, selected);
    for (const std::string& key : mine) {
      CrowdGroup group = make_group(key, groups[key].front());
      for (const Condition& c : groups[key]) {
        manifest.entries.push_back(run_condition(group, c));
        progress.advance();
      }
    }
    progress.finish();
    summary_.conditions = static_cast<int>(selected);
    summary_.manifest =
        opt_.out_dir / (opt_.shard.count > 1 ? "manifest.shard-" + std::to_string(opt_.shard.index) + "-of-" +
                                                   std::to_string(opt_.shard.count) + ".csv"
                                             : std::string("manifest.csv"));
    write_manifest(manifest, summary_.manifest.string());
    return summary_;
  }

 private:
  void copy_spec() {
    const fs::path dst = opt_.out_dir / "spec.yaml";
    if (spec_.source_path.empty() || !fs::exists(spec_.source_path)) return;
    std::ifstream in(spec_.source_path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    write_file_atomic(dst, ss.str());
  }

  CrowdGroup make_group(const std::string& key, const Condition& first) {
    CrowdGroup g;
    g.key = key;
    g.dir = opt_.out_dir / "crowds" / key;
    fs::create_directories(g.dir);
    g.crowd_condition = crowd_condition(spec_, first);
    // Stage input hashes: each stage's own parameters plus its upstream hash.
    json crowd_params;
    crowd_params["levels"] = level_json(g.crowd_condition);
    crowd_params["scenario"] = spec_.scenario.type;
    crowd_params["seed"] = g.crowd_condition.seed;
    crowd_params["spec"] = spec_.source_hash;  // scenario/crowd sections live in the spec text
    g.crowd_hash = stage_input_hash("crowd", crowd_params, {});
    // The MPFB2 asset folder may come from the environment, so it is an input of its own.
    g.baseline_hash = stage_input_hash(
        "animation", json{{"spec", spec_.source_hash}, {"body_model_path", spec_.animation.body_model_path}},
        {g.crowd_hash});
    g.ours_hash = stage_input_hash("correction",
                                   json{{"damping", spec_.correction.damping},
                                        {"stiffness", spec_.correction.stiffness},
                                        {"contact_stiffness", spec_.correction.collision_stiffness}},
                                   {g.baseline_hash});
    return g;
  }

  bool up_to_date(const fs::path& out, const std::string& hash) {
    const bool ok = !opt_.force && output_up_to_date(out, hash);
    (ok ? summary_.stages_skipped : summary_.stages_run)++;
    return ok;
  }

  bool is_manifold(const CrowdGroup& g) const {
    return effective_scenario_type(spec_, g.crowd_condition) == "manifold";
  }

  const ScenarioResult& scenario(CrowdGroup& g) {
    if (g.scenario) return *g.scenario;
    if (is_manifold(g)) {
      // Crowds on surfaces come from the surface stage (seed 002), with their 3D frames.
      ManifoldScenario m = generate_manifold_scenario(spec_, g.crowd_condition);
      g.surface = std::move(m.surface);
      g.scenario = std::move(m.result);
    } else {
      g.scenario = generate_scenario(spec_, g.crowd_condition);
    }
    return *g.scenario;
  }

  void write_trajectories(CrowdGroup& g) {
    const fs::path out = g.dir / "trajectories.csv";
    const fs::path surface_out = g.dir / "surface_trajectories.csv";
    const bool manifold = is_manifold(g);
    if (up_to_date(out, g.crowd_hash) && (!manifold || output_up_to_date(surface_out, g.crowd_hash))) return;
    const std::string text = trajectories_csv(scenario(g).trajectories);
    write_file_atomic(out, text);
    record_provenance(out, "crowd", g.crowd_hash, context_);
    if (manifold) {
      write_file_atomic(surface_out, surface_trajectories_csv(g.surface, spec_.fps));
      record_provenance(surface_out, "crowd", g.crowd_hash, context_);
    }
  }

  const CrowdAnimation& baseline(CrowdGroup& g) {
    const fs::path out = g.dir / "baseline.glb";
    if (g.baseline) return *g.baseline;
    write_trajectories(g);
    if (up_to_date(out, g.baseline_hash)) {
      g.baseline = read_crowd_glb(out.string());
      return *g.baseline;
    }
    CrowdAnimation crowd = animate_scenario(spec_, g.crowd_condition, g.key, scenario(g), g.surface);
    write_output_via_temporary(out, [&](const fs::path& tmp) { write_crowd_glb(crowd, tmp.string()); });
    record_provenance(out, "animation", g.baseline_hash, context_);
    g.baseline = std::move(crowd);
    return *g.baseline;
  }

  const CrowdAnimation& corrected(CrowdGroup& g) {
    const fs::path out = g.dir / "ours.glb";
    if (g.ours) return *g.ours;
    const CrowdAnimation& input = baseline(g);
    if (up_to_date(out, g.ours_hash)) {
      g.ours = read_crowd_glb(out.string());
      return *g.ours;
    }
    CorrectorParams params;
    if (spec_.correction.stiffness > 0) params.stiffness = spec_.correction.stiffness;
    params.damping = spec_.correction.damping;
    if (spec_.correction.collision_stiffness > 0)
      params.contact_stiffness = spec_.correction.collision_stiffness;
    Progress progress("correct " + g.key, static_cast<size_t>(input.frame_count()));
    CorrectionReport report;
    CrowdAnimation out_crowd = correct_crowd(input, params, &progress, &report);
    if (report.rejected_steps > 0)
      spdlog::warn("{}: the corrector rejected {} of {} steps and kept the last stable state", g.key,
                   report.rejected_steps, report.frames);
    write_output_via_temporary(out, [&](const fs::path& tmp) { write_crowd_glb(out_crowd, tmp.string()); });
    record_provenance(out, "correction", g.ours_hash, context_);
    g.ours = std::move(out_crowd);
    return *g.ours;
  }

  static std::string method_of(const Condition& c) { return c.text("method", "baseline"); }

  const json& metrics(CrowdGroup& g, const std::string& method) {
    auto it = g.metrics.find(method);
    if (it != g.metrics.end()) return it->second;
    const fs::path out = g.dir / (method + ".metrics.json");
    const std::string hash =
        stage_input_hash("metrics", json::object(), {method == "ours" ? g.ours_hash : g.baseline_hash});
    json j;
    if (up_to_date(out, hash)) {
      std::ifstream in(out);
      j = json::parse(in);
    } else {
      const CrowdAnimation& crowd = method == "ours" ? corrected(g) : baseline(g);
      const CrowdMetrics m = measure_crowd(crowd);
      j = crowd_metrics_json(m, false);
      write_file_atomic(out, j.dump(2) + "\n");
      record_provenance(out, "metrics", hash, context_);
    }
    return g.metrics[method] = j;
  }

  /// What every clip of the group is framed by: the crowd stage's trajectories (3D surface frames for
  /// manifold crowds) and the body heights of the animation stage, which the correction stage keeps.
  /// So `baseline` and `ours` of a condition get the identical camera. Inputs: crowd_hash, baseline_hash.
  const stimuli::CrowdExtent& extent(CrowdGroup& g) {
    if (g.extent) return *g.extent;
    const std::vector<double> heights = stimuli::body_heights_m(baseline(g));
    const ScenarioResult& s = scenario(g);
    g.extent = stimuli::crowd_extent(g.surface.empty() ? stimuli::character_tracks(s.trajectories, heights)
                                                       : stimuli::character_tracks(g.surface, heights),
                                     s.trajectories.fps);
    return *g.extent;
  }

  static void link_or_copy(const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::remove(to, ec);
    fs::create_hard_link(from, to, ec);
    if (ec) fs::copy_file(from, to, fs::copy_options::overwrite_existing);
  }

  Renderer& renderer() {
    if (!renderer_) renderer_ = std::make_unique<Renderer>();
    return *renderer_;
  }

  RenderOptions render_options() const {
    RenderOptions r;
    r.width = spec_.render.width;
    r.height = spec_.render.height;
    r.crf = spec_.render.crf;
    r.scene.overlap = spec_.render.overlap;
    r.scene.msaa_samples = spec_.render.msaa;
    r.scene.background = parse_hex_colour(spec_.render.background, "render.background");
    r.scene.fog_density = spec_.render.fog ? 0.02 : 0.0;
    r.viewpoint_overrides = spec_.render.viewpoint_overrides;
    r.character_files = spec_.render.characters;
    return r;
  }

  StimulusEntry run_condition(CrowdGroup& g, const Condition& c) {
    const std::string method = method_of(c);
    const fs::path dir = opt_.out_dir / "conditions" / c.id;
    fs::create_directories(dir);
    const std::string anim_hash = method == "ours" ? g.ours_hash : g.baseline_hash;
    const fs::path glb_src = g.dir / (method == "ours" ? "ours.glb" : "baseline.glb");
    const CrowdAnimation& crowd = method == "ours" ? corrected(g) : baseline(g);
    link_or_copy(glb_src, dir / "crowd.glb");
    const json& m = spec_.outputs.metrics ? metrics(g, method) : json::object();
    if (spec_.outputs.metrics) link_or_copy(g.dir / (method + ".metrics.json"), dir / "metrics.json");

    StimulusEntry e;
    e.id = c.id;
    for (const auto& [name, level] : c.levels) e.factors[name] = level.text;
    e.practice = c.practice;
    e.mean_overlap_l = m.value("mean_character_overlap_l", -1.0);
    e.v_i_m = m.value("volume_index_m", -1.0);
    e.collisions = m.value("collision_count", -1);
    e.frames = crowd.frame_count();
    e.duration_s = crowd.duration_s();
    if (!spec_.outputs.video) return e;

    const std::string viewpoint = c.text("viewpoint", default_viewpoint());
    RenderOptions ro = render_options();
    // render.frames_png: the rendered frames themselves, before H.264 (tests hash their pixels).
    if (spec_.render.frames_png) ro.frames_png_dir = (dir / "frames").string();
    const fs::path clip = dir / "clip.mp4";
    const fs::path sidecar = stimuli::clip_sidecar_path(clip);
    // The camera depends on the shared framing data (trajectories and heights: baseline_hash covers
    // both), the framing rule, the viewpoint, the image size and the overrides (in the spec).
    const std::string render_hash = stage_input_hash("render",
                                                     json{{"viewpoint", viewpoint},
                                                          {"width", ro.width},
                                                          {"height", ro.height},
                                                          {"crf", ro.crf},
                                                          {"msaa", ro.scene.msaa_samples},
                                                          {"overlap", ro.scene.overlap},
                                                          {"characters", ro.character_files},
                                                          {"framing", kFramingRule},
                                                          {"spec", spec_.source_hash}},
                                                     {anim_hash, g.baseline_hash});
    const bool clip_done = up_to_date(clip, render_hash);
    if (!clip_done || !output_up_to_date(sidecar, render_hash)) {
      const stimuli::Viewpoint view(viewpoint, extent(g), ro.width, ro.height, ro.viewpoint_overrides);
      if (!clip_done) {
        write_output_via_temporary(
            clip, [&](const fs::path& tmp) { render_clip(renderer(), crowd, ro, view, tmp.string()); });
        record_provenance(clip, "render", render_hash, context_);
      }
      write_file_atomic(sidecar, stimuli::clip_sidecar(view, crowd.frame_count(), crowd).dump(2) + "\n");
      record_provenance(sidecar, "render", render_hash, context_);
    }
    if (spec_.outputs.contact_sheet) {
      const fs::path sheet = g.dir / (method + ".contact_sheet.png");
      const std::string sheet_hash = stage_input_hash(
          "contact_sheet", json{{"w", ro.width}, {"h", ro.height}, {"framing", kFramingRule}},
          {anim_hash, g.baseline_hash});
      if (!up_to_date(sheet, sheet_hash)) {
        write_output_via_temporary(sheet, [&](const fs::path& tmp) {
          write_contact_sheet(renderer(), crowd, ro, crowd.frame_count() / 2, tmp.string(), &extent(g));
        });
        record_provenance(sheet, "contact_sheet", sheet_hash, context_);
      }
    }
    e.file = fs::relative(clip, opt_.out_dir).string();
    e.width = ro.width;
    e.height = ro.height;
    e.sha256 = sha256_file_hex(clip.string());
    return e;
  }

  std::string default_viewpoint() const {
    const std::string type = spec_.scenario.type;
    if (type == "pair_crossing") return "pair";
    if (type == "flow_a") return "tracking";
    return "V1";
  }

  const ExperimentSpec& spec_;
  RunOptions opt_;
  ProvenanceContext context_;
  RunSummary summary_;
  std::unique_ptr<Renderer> renderer_;
};

}  // namespace

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

Condition crowd_condition(const ExperimentSpec& spec, const Condition& condition) {
  Condition c = condition;
  c.seed = derive_seed(spec.seed, "crowd/" + crowd_key(condition));
  return c;
}

std::string crowd_key(const Condition& condition) {
  std::string key;
  for (const auto& [name, level] : condition.levels) {
    if (is_presentation_factor(name)) continue;
    key += name + "-" + level.text + "_";
  }
  key += "rep-" + std::to_string(condition.repetition);
  return condition.practice ? "practice_" + key : key;
}

RunSummary run_experiment(const ExperimentSpec& spec, const RunOptions& options) {
  return Runner(spec, options).run();
}

}  // namespace crowdlab::cli
