// The YAML -> ExperimentSpec boundary. Every key is checked (unknown keys get a did-you-mean), every
// type and range, and every referenced file; all problems are collected and thrown together as one
// SpecError. The key reference, with defaults, ranges and units, is docs/spec-reference.md.
#include "framework/spec/load_experiment_spec.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string_view>

#include "framework/core/control_characters.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/library_error.hpp"
#include "framework/core/mpfb2_asset_dir.hpp"
#include "framework/core/sha256.hpp"
#include "framework/core/utf8_validity.hpp"
#include "framework/core/viewpoint_catalogue.hpp"
#include "framework/spec/estimate_work.hpp"
#include "framework/spec/parse_factor.hpp"
#include "framework/spec/parse_protocol.hpp"
#include "framework/spec/surface_scene_names.hpp"
#include "framework/spec/work_limits.hpp"
#include "framework/spec/yaml_flow_nesting.hpp"
#include "framework/spec/yaml_section.hpp"

namespace crowdlab {
namespace {

constexpr int kFormatVersion = 1;

std::string join_lines(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += (out.empty() ? "" : "\n") + l;
  return out;
}

// Read-only child lookup (a non-const operator[] would insert the key).
YAML::Node child(const YAML::Node& map, const std::string& key) {
  if (!map.IsMap()) return YAML::Node(YAML::NodeType::Undefined);
  return map[key];
}

bool has_file_extension(const std::string& s) {
  return s.find('/') != std::string::npos || std::filesystem::path(s).has_extension();
}

void parse_scenario(YamlSection s, ExperimentSpec& spec) {
  ScenarioSpec& sc = spec.scenario;
  s.allow_keys({"type", "area", "stage_direction_deg", "walk_speed_mps", "initial_spacing_m", "passing_side",
                "mesh", "agents"});
  s.choice("type", sc.type);
  YamlSection area = s.section("area");
  area.allow_keys({"width_m", "depth_m"});
  area.number("width_m", sc.width_m, Range::positive(1000.0));
  area.number("depth_m", sc.depth_m, Range::positive(1000.0));
  s.number("stage_direction_deg", sc.stage_direction_deg, Range{-360.0, 360.0});
  // 3 m/s is a fast run; human preferred walking speed is ~1.3 m/s (Bohannon 1997).
  s.number("walk_speed_mps", sc.walk_speed_mps, Range::positive(3.0));
  s.number("initial_spacing_m", sc.initial_spacing_m, Range::positive(10.0));
  s.choice("passing_side", sc.passing_side);
  s.integer("agents", sc.agents, 0, 100000);
  if (s.has("mesh")) {
    std::string mesh;
    s.string("mesh", mesh);
    // Checked here as `run` would check it (issue 33): a name must be a built-in scene, a file an existing
    // .obj, .gltf or .glb (`mesh: /etc/passwd` passed validate and failed in run without a line).
    if (has_file_extension(mesh)) {
      const std::string ext = std::filesystem::path(mesh).extension().string();
      if (std::find(kSurfaceMeshExtensions.begin(), kSurfaceMeshExtensions.end(), ext) ==
          kSurfaceMeshExtensions.end())
        s.diagnostics().error(s.get("mesh"), s.child_path("mesh"),
                              "'" + mesh + "' is not a mesh file (.obj, .gltf or .glb)");
      else if (auto p =
                   resolve_existing_path(s.diagnostics(), s.get("mesh"), s.child_path("mesh"), mesh, false))
        sc.mesh = *p;
    } else if (std::find(kSurfaceSceneNames.begin(), kSurfaceSceneNames.end(), mesh) ==
               kSurfaceSceneNames.end()) {
      std::string names;
      for (const auto n : kSurfaceSceneNames) names += (names.empty() ? "" : ", ") + std::string(n);
      s.diagnostics().error(s.get("mesh"), s.child_path("mesh"),
                            "unknown surface scene '" + mesh + "' (expected one of " + names +
                                ", or an .obj, .gltf or .glb file)");
    } else {
      sc.mesh = mesh;
    }
  }
}

/// crowd.cost_weights: the cost model's keys (did-you-mean on a typo) and each one's range, checked here so
/// that `validate` refuses what the cost model would refuse minutes into `run`.
void parse_cost_weights(YamlSection w, CrowdSpec& c) {
  if (!w.present()) return;
  w.allow_keys({"goal", "smoothness", "separation", "walls", "sigma_m", "lookahead_s", "iterations"});
  const auto weight = [&](const char* key, const Range& range) {
    if (!w.has(key)) return;
    double v = 0.0;
    w.number(key, v, range);
    c.cost_weights[key] = v;
  };
  for (const char* key : {"goal", "smoothness", "separation", "walls"}) weight(key, Range::non_negative());
  for (const char* key : {"sigma_m", "lookahead_s"}) weight(key, Range::positive());
  if (w.has("iterations")) {
    int n = 1;
    w.integer("iterations", n, 1, 100);
    c.cost_weights["iterations"] = n;
  }
}

void parse_crowd(YamlSection s, ExperimentSpec& spec) {
  CrowdSpec& c = spec.crowd;
  s.allow_keys({"model", "agent_radius_m", "neighbor_distance_m", "max_neighbors", "time_horizon_s",
                "obstacle_time_horizon_s", "max_speed_mps", "dt_s", "cost_weights", "overlap_free",
                "personal_space_m"});
  s.choice("model", c.model);
  s.number("agent_radius_m", c.agent_radius_m, Range::positive(1.0));
  s.number("neighbor_distance_m", c.neighbor_distance_m, Range::positive(100.0));
  s.integer("max_neighbors", c.max_neighbors, 1, 1000);
  s.number("time_horizon_s", c.time_horizon_s, Range::positive(60.0));
  s.number("obstacle_time_horizon_s", c.obstacle_time_horizon_s, Range::positive(60.0));
  s.number("max_speed_mps", c.max_speed_mps, Range::positive(10.0));
  s.number("dt_s", c.dt_s, Range::positive(1.0));
  s.boolean("overlap_free", c.overlap_free);
  s.number("personal_space_m", c.personal_space_m, Range::non_negative(5.0));
  if (c.overlap_free && c.model != CrowdModel::orca)
    s.diagnostics().error(s.get("overlap_free"), s.child_path("overlap_free"),
                          "applies to model orca only (model is '" + std::string(kind_name(c.model)) + "')");
  parse_cost_weights(s.section("cost_weights"), c);
}

void parse_walk_clips(YamlSection& s, AnimationSpec& a) {
  if (!s.has("walk_clips")) return;
  SpecDiagnostics& diag = s.diagnostics();
  const YAML::Node list = s.get("walk_clips");
  const std::string path = s.child_path("walk_clips");
  if (!list.IsSequence()) {
    diag.error(list, path, "expected a list of {file, speed_mps}, got " + describe_node(list));
    return;
  }
  for (size_t i = 0; i < list.size(); ++i) {
    YamlSection clip(diag, list[i], path + "[" + std::to_string(i) + "]");
    if (!clip.present()) continue;
    clip.allow_keys({"file", "speed_mps"});
    std::string file;
    double speed = 0.0;
    if (clip.require("file")) clip.existing_path("file", file, false);
    if (clip.require("speed_mps")) clip.number("speed_mps", speed, Range::positive(10.0));
    if (!file.empty() && speed > 0.0) {
      a.walk_clips.push_back(file);
      a.walk_clip_speeds_mps.push_back(speed);
    }
  }
}

void parse_animation(YamlSection s, ExperimentSpec& spec) {
  AnimationSpec& a = spec.animation;
  SpecDiagnostics& diag = s.diagnostics();
  s.allow_keys({"body_model", "female_fraction", "motion", "walk_clips", "dance_clips", "ttca_threshold_s",
                "dtca_threshold_m", "collision_proxies"});
  const bool body_model_map = s.has("body_model") && s.get("body_model").IsMap();
  if (body_model_map) {
    YamlSection bm = s.section("body_model");
    bm.allow_keys({"type", "path"});
    bm.choice("type", a.body_model);
    bm.existing_path("path", a.body_model_path, true);
  } else {
    s.choice("body_model", a.body_model);
  }
  if (a.body_model == BodyModel::mpfb2 && a.body_model_path.empty() &&
      !(body_model_map && s.section("body_model").has("path"))) {
    const std::filesystem::path dir = default_mpfb2_dir();
    if (!std::filesystem::is_directory(dir))
      diag.error(s.get("body_model"), s.child_path("body_model"),
                 "mpfb2: the asset folder '" + dir.string() +
                     "' (CROWDLAB_MPFB2, else the shipped framework/body/assets/mpfb2) is not a directory; "
                     "set body_model.path or CROWDLAB_MPFB2");
    else
      a.body_model_path = dir.string();
  }
  s.number("female_fraction", a.female_fraction, Range{0.0, 1.0});
  s.choice("motion", a.motion);
  s.choice("collision_proxies", a.collision_proxies);
  parse_walk_clips(s, a);
  if (s.has("dance_clips")) {
    const YAML::Node list = s.get("dance_clips");
    if (!list.IsSequence()) {
      diag.error(list, s.child_path("dance_clips"), "expected a list of files, got " + describe_node(list));
    } else {
      for (size_t i = 0; i < list.size(); ++i) {
        const std::string path = s.child_path("dance_clips") + "[" + std::to_string(i) + "]";
        if (auto f = parse_string(diag, list[i], path))
          if (auto p = resolve_existing_path(diag, list[i], path, *f, false)) a.dance_clips.push_back(*p);
      }
    }
  }
  if (a.motion == MotionSource::clips && !s.has("walk_clips") && !s.has("dance_clips"))
    diag.error(s.get("motion"), s.child_path("motion"), "motion: clips needs walk_clips or dance_clips");
  // seed 001 §4.1: ttca_th = 0.7 s, dtca_th = 0.6 m.
  s.number("ttca_threshold_s", a.ttca_threshold_s, Range::positive(10.0));
  s.number("dtca_threshold_m", a.dtca_threshold_m, Range::positive(10.0));
}

void parse_correction(YamlSection s, ExperimentSpec& spec) {
  s.allow_keys({"stiffness", "damping", "collision_stiffness"});
  s.number("stiffness", spec.correction.stiffness, Range::non_negative());
  s.number("damping", spec.correction.damping, Range::non_negative());
  s.number("collision_stiffness", spec.correction.collision_stiffness, Range::non_negative());
}

void parse_stimulus_check(YamlSection s, StimulusCheckSpec& c) {
  if (!s.present()) return;
  s.allow_keys({"crowd_in_frame_min", "character_height_px_min", "overhead_height_px_min",
                "seam_step_ratio_max", "baseline_overlap_frames_min", "overlap_every_frames"});
  s.number("crowd_in_frame_min", c.crowd_in_frame_min, Range{0.0, 1.0});
  s.number("character_height_px_min", c.character_height_px_min, Range::non_negative(1e5));
  s.number("overhead_height_px_min", c.overhead_height_px_min, Range::non_negative(1e5));
  s.number("seam_step_ratio_max", c.seam_step_ratio_max, Range::positive(1e6));
  s.number("baseline_overlap_frames_min", c.baseline_overlap_frames_min, Range{0.0, 1.0});
  s.integer("overlap_every_frames", c.overlap_every_frames, 0, 100000);
}

void parse_render(YamlSection s, ExperimentSpec& spec) {
  RenderSpec& r = spec.render;
  SpecDiagnostics& diag = s.diagnostics();
  s.allow_keys(
      {"crf", "msaa", "overlap", "frames_png", "background", "fog", "viewpoints", "characters", "check"});
  s.integer("crf", r.crf, 0, 51);   // the H.264 constant-rate-factor range
  s.integer("msaa", r.msaa, 1, 8);  // samples per pixel (the GL driver rounds up to one it has)
  s.boolean("overlap", r.overlap);
  s.boolean("frames_png", r.frames_png);
  s.boolean("fog", r.fog);
  if (s.has("characters")) {
    const YAML::Node list = s.get("characters");
    if (!list.IsSequence() || list.size() == 0) {
      diag.error(list, s.child_path("characters"),
                 "expected a list of glTF character files, got " + describe_node(list));
    } else {
      for (size_t i = 0; i < list.size(); ++i) {
        const std::string path = s.child_path("characters") + "[" + std::to_string(i) + "]";
        if (auto f = parse_string(diag, list[i], path))
          if (auto p = resolve_existing_path(diag, list[i], path, *f, false)) r.characters.push_back(*p);
      }
    }
  }
  if (s.has("background")) {
    std::string bg;
    s.string("background", bg);
    bool ok = bg.size() == 7 && bg[0] == '#';
    for (size_t i = 1; ok && i < bg.size(); ++i) ok = std::isxdigit(static_cast<unsigned char>(bg[i])) != 0;
    if (ok)
      r.background = bg;
    else
      diag.error(s.get("background"), s.child_path("background"),
                 "expected a colour '#rrggbb', got '" + bg + "'");
  }
  parse_stimulus_check(s.section("check"), r.check);
  YamlSection vps = s.section("viewpoints");
  if (vps.present()) {
    vps.allow_keys(viewpoint_names());
    for (auto it = vps.node().begin(); it != vps.node().end(); ++it) {
      const std::string name = it->first.Scalar();
      const std::optional<ViewpointId> id = find_viewpoint(name);
      if (!id) continue;  // reported by allow_keys
      std::vector<double> v;
      vps.number_list(name, v, Range{-1e4, 1e4});
      if (v.empty()) continue;
      if (v.size() != 7) {
        diag.error(it->second, vps.child_path(name),
                   "expected 7 numbers [px, py, pz, tx, ty, tz, fov_deg], got " + std::to_string(v.size()));
        continue;
      }
      CameraPlacement placement{};
      std::copy(v.begin(), v.end(), placement.begin());
      if (const std::string problem = camera_placement_problem(placement); !problem.empty())
        diag.error(it->second, vps.child_path(name), problem);
      else
        r.viewpoint_overrides[*id] = placement;
    }
  }
}

void parse_outputs(YamlSection s, ExperimentSpec& spec) {
  s.allow_keys({"video", "contact_sheet", "metrics"});
  s.boolean("video", spec.outputs.video);
  s.boolean("contact_sheet", spec.outputs.contact_sheet);
  s.boolean("metrics", spec.outputs.metrics);
}

void parse_resolution(YamlSection& top, ExperimentSpec& spec) {
  if (!top.has("resolution")) return;
  SpecDiagnostics& diag = top.diagnostics();
  const YAML::Node n = top.get("resolution");
  if (!n.IsSequence() || n.size() != 2) {
    diag.error(n, "resolution", "expected [width, height] in pixels, got " + describe_node(n));
    return;
  }
  // Even sizes: H.264 with 4:2:0 chroma needs them; 7680 is 8K UHD.
  auto w = parse_integer(diag, n[0], "resolution[0]", 16, 7680);
  auto h = parse_integer(diag, n[1], "resolution[1]", 16, 4320);
  if (w && *w % 2)
    diag.error(n[0], "resolution[0]", "width must be even (H.264 4:2:0), got " + std::to_string(*w));
  if (h && *h % 2)
    diag.error(n[1], "resolution[1]", "height must be even (H.264 4:2:0), got " + std::to_string(*h));
  if (w && h && *w % 2 == 0 && *h % 2 == 0) {
    spec.render.width = *w;
    spec.render.height = *h;
  }
}

void parse_factors(YamlSection& top, ExperimentSpec& spec) {
  YamlSection f = top.section("factors");
  if (!f.present()) return;
  f.allow_keys(known_factor_names());
  for (auto it = f.node().begin(); it != f.node().end(); ++it) {
    const std::string name = it->first.Scalar();
    bool known = false;
    for (const std::string& k : known_factor_names()) known = known || k == name;
    if (!known || spec.factor(name)) continue;  // reported by allow_keys
    if (auto factor = parse_factor(top.diagnostics(), name, it->second, f.child_path(name)))
      spec.factors.push_back(*factor);
  }
}

// The mark (0-based line and column, in bytes) of byte `offset` of `text`.
YAML::Mark mark_at(const std::string& text, size_t offset) {
  YAML::Mark m;
  m.pos = static_cast<int>(offset);
  for (size_t i = 0; i < offset; ++i) {
    if (text[i] == '\n') {
      ++m.line;
      m.column = 0;
    } else {
      ++m.column;
    }
  }
  return m;
}

// Byte offset of a `---` line that starts a second YAML document, or npos. At column 0 `---` is always a
// document marker (top-level block scalars are indented); a first marker before any content is allowed.
// (A text scan: yaml-cpp's LoadAll misbehaved on the loader's mangled-spec test input.)
size_t second_document_start(const std::string& text) {
  bool content = false;
  for (size_t line = 0; line < text.size();) {
    const size_t end = std::min(text.find('\n', line), text.size());
    const std::string_view l(text.data() + line, end - line);
    const bool marker =
        l.substr(0, 3) == "---" && (l.size() == 3 || l[3] == ' ' || l[3] == '\t' || l[3] == '\r');
    if (marker && content) return line;
    const size_t first = l.find_first_not_of(" \t\r");
    if (!marker && first != std::string_view::npos && l[first] != '#' && l[first] != '%') content = true;
    line = end + 1;
  }
  return std::string::npos;
}

// yaml-cpp refuses lists and maps nested deeper than its limit with "bad file", at a position that for
// flow collections is the end of the nest or the start of the file: point at the nest instead.
void report_deep_nesting(SpecDiagnostics& diag, const std::string& text, const YAML::DeepRecursion& e) {
  // Any flow nest of 100 levels is pathological (a spec needs fewer than 10); without one, the nest is
  // in block style, where yaml-cpp's own mark is right.
  constexpr std::size_t kPathologicalFlowDepth = 100;
  const std::size_t start = deep_flow_nesting_start(text, kPathologicalFlowDepth);
  diag.error(start == std::string::npos ? e.mark : mark_at(text, start), "",
             "nesting too deep: lists and maps nest more than " + std::to_string(kYamlParserDepthLimit) +
                 " levels from here (the YAML parser's limit; a spec needs fewer than 10)");
}

// A spec is UTF-8 text (a UTF-8 byte-order mark is allowed). UTF-16 and Latin-1 files would otherwise be
// misread or accepted with garbled names.
void check_encoding(SpecDiagnostics& diag, const std::string& text) {
  const auto starts_with = [&](const char* bom) { return text.rfind(bom, 0) == 0; };
  if (starts_with("\xFF\xFE") || starts_with("\xFE\xFF")) {
    diag.error(mark_at(text, 0), "",
               "the file is UTF-16 (it starts with a UTF-16 byte-order mark); save it as UTF-8");
    return;
  }
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    diag.error(mark_at(text, nul), "", "a NUL byte: the file is binary or UTF-16, not UTF-8 text");
    return;
  }
  if (const size_t bad = first_invalid_utf8_byte(text); bad != std::string::npos) {
    char code[8];
    std::snprintf(code, sizeof code, "0x%02X", static_cast<unsigned>(static_cast<unsigned char>(text[bad])));
    diag.error(mark_at(text, bad), "",
               std::string("byte ") + code + " is not valid UTF-8; save the file as UTF-8");
  }
}

// Checks that need several sections at once.
/// The scenario kinds the conditions use: the `scenario` factor's levels (A, B: the flows), else
/// scenario.type (as type_condition.cpp reads them).
std::vector<ScenarioKind> scenario_kinds_used(const ExperimentSpec& spec) {
  const Factor* f = spec.factor("scenario");
  if (!f) return {spec.scenario.type};
  std::vector<ScenarioKind> kinds;
  for (const FactorLevel& l : f->levels) {
    std::optional<ScenarioKind> k = l.text == "A"   ? ScenarioKind::flow_a
                                    : l.text == "B" ? ScenarioKind::flow_b
                                                    : parse_kind<ScenarioKind>(l.text);
    if (k) kinds.push_back(*k);
  }
  return kinds;
}

bool uses_kind(const ExperimentSpec& spec, ScenarioKind kind) {
  const std::vector<ScenarioKind> kinds = scenario_kinds_used(spec);
  return std::find(kinds.begin(), kinds.end(), kind) != kinds.end();
}

/// What the crowd stage needs per scenario kind, whether the kind is scenario.type or a `scenario` factor's
/// level: the pair's distance (pair_crossing), a mesh (manifold).
void check_scenario_needs(YamlSection& top, const ExperimentSpec& spec) {
  SpecDiagnostics& diag = top.diagnostics();
  const YAML::Node scenario = top.has("scenario")  ? top.get("scenario")
                              : top.has("factors") ? top.get("factors")
                                                   : top.node();
  if (uses_kind(spec, ScenarioKind::pair_crossing) && !spec.factor("distance"))
    diag.error(top.has("factors") ? top.get("factors") : top.node(), "factors",
               "a pair_crossing scenario needs a `distance` factor (metres)");
  if (uses_kind(spec, ScenarioKind::manifold) && spec.scenario.mesh.empty() &&
      !(child(scenario, "mesh").IsDefined()))
    diag.error(scenario, "scenario.mesh", "a manifold scenario needs a mesh (scene name or file)");
}

/// A manifold scenario's crowd (framework/surface/generate_manifold_scenario.hpp): its avoidance models and
/// the surface crowd's ranges, checked here so that `validate` refuses what the surface stage would.
void check_manifold_crowd(YamlSection& top, const ExperimentSpec& spec) {
  if (!uses_kind(spec, ScenarioKind::manifold)) return;
  SpecDiagnostics& diag = top.diagnostics();
  const CrowdSpec& c = spec.crowd;
  const auto require = [&](bool ok, const char* section, const char* key, const std::string& range) {
    if (!ok)
      diag.error(child(child(top.node(), section), key), std::string(section) + "." + key,
                 "a manifold scenario needs " + range);
  };
  require(c.model == CrowdModel::orca || c.model == CrowdModel::social, "crowd", "model",
          "'orca' or 'social', not '" + std::string(kind_name(c.model)) + "'");
  require(c.neighbor_distance_m <= 10, "crowd", "neighbor_distance_m", "a value in (0, 10] m");
  require(c.max_neighbors <= 32, "crowd", "max_neighbors", "a value in [1, 32]");
  require(c.time_horizon_s <= 10, "crowd", "time_horizon_s", "a value in (0, 10] s");
  require(2 * c.agent_radius_m <= 1.8, "crowd", "agent_radius_m", "a radius of at most 0.9 m (1.8 m agents)");
  require(spec.scenario.walk_speed_mps <= 3, "scenario", "walk_speed_mps", "a value in (0, 3] m/s");
}

void check_consistency(YamlSection& top, ExperimentSpec& spec) {
  SpecDiagnostics& diag = top.diagnostics();
  check_manifold_crowd(top, spec);
  check_scenario_needs(top, spec);
  const Factor* density = spec.factor("density");
  bool area_scenario = false;
  for (ScenarioKind k : scenario_kinds_used(spec)) area_scenario = area_scenario || is_area_scenario(k);
  if (density && area_scenario && !spec.factor("characters")) {
    const double area = spec.scenario.width_m * spec.scenario.depth_m;
    for (const FactorLevel& l : density->levels)
      if (l.number && std::lround(*l.number * area) < 1)
        diag.error(child(child(top.node(), "factors"), "density"), "factors.density",
                   "density " + l.text + " on a " + format_number(area) + " m^2 area gives no character");
  }
  for (const auto& [id, placement] : spec.render.viewpoint_overrides) {
    (void)placement;
    const std::string name(viewpoint_name(id));
    const Factor* vp = spec.factor("viewpoint");
    bool used = false;
    if (vp)
      for (const FactorLevel& l : vp->levels) used = used || l.text == name;
    if (!used)
      diag.error(child(child(child(top.node(), "render"), "viewpoints"), name), "render.viewpoints." + name,
                 "no condition uses viewpoint '" + name + "' (add it to factors.viewpoint)");
  }
}

// Estimates of the work a spec asks for, refused beyond the documented limits (load_experiment_spec.hpp).
void check_work_limits(YamlSection& top, const ExperimentSpec& spec) {
  SpecDiagnostics& diag = top.diagnostics();
  const auto at = [&](const std::string& key) { return top.has(key) ? top.get(key) : top.node(); };
  const SpecWork work = estimate_spec_work(spec);
  if (work.conditions > kMaxConditions)
    diag.error(at("factors"), "factors",
               "the factor levels x " + std::to_string(spec.repetitions) + " repetitions make " +
                   format_number(work.conditions) + " conditions, more than the limit of " +
                   format_number(kMaxConditions) + "; split the study into several specs");
  // Practice conditions are rendered too (issue 32: a practice block multiplying to 1e7 conditions
  // passed `validate` and ran `plan` out of memory).
  const double all = work.conditions + work.practice_conditions;
  if (work.conditions <= kMaxConditions && all > kMaxConditions)
    diag.error(top.has("protocol") ? top.get("protocol") : top.node(), "protocol.practice",
               format_number(work.conditions) + " conditions + " + format_number(work.practice_conditions) +
                   " practice conditions (the practice levels, crossed with the blocks) make " +
                   format_number(all) + ", more than the limit of " + format_number(kMaxConditions) +
                   "; list fewer practice levels or split the study");
  const auto problem = crowd_limit_problem(
      "the largest crowd", work.largest_crowd, work.frames,
      "lower the density (density x area, or a flow's lattice of spacing 1/sqrt(density) or "
      "initial_spacing_m over the area), the characters factor or scenario.agents",
      "shorten the clip (duration_s x fps frames), lower fps or the crowd");
  if (problem)
    diag.error(at(work.largest_crowd > kMaxCharactersPerCrowd ? "factors" : "duration_s"),
               work.largest_crowd > kMaxCharactersPerCrowd ? "factors" : "duration_s", *problem);
}

}  // namespace

SpecError::SpecError(std::vector<std::string> messages)
    : InputError(join_lines(messages)), messages_(std::move(messages)) {}

ExperimentSpec load_experiment_spec_text(const std::string& yaml_text, const std::string& source_name,
                                         const std::string& base_dir) {
  SpecDiagnostics diag{source_name, base_dir, {}, {}};
  check_encoding(diag, yaml_text);
  if (!diag.messages.empty()) throw SpecError(diag.sorted_messages());
  YAML::Node root;
  try {
    // A UTF-8 byte-order mark (some Windows editors write one) is not part of the first key.
    const bool bom = yaml_text.rfind("\xEF\xBB\xBF", 0) == 0;
    root = YAML::Load(bom ? yaml_text.substr(3) : yaml_text);
    if (const size_t second = second_document_start(yaml_text); second != std::string::npos)
      diag.error(
          mark_at(yaml_text, second), "",
          "a second YAML document starts here; a spec is one document (only the first was read before)");
  } catch (const YAML::DeepRecursion& e) {
    report_deep_nesting(diag, yaml_text, e);
  } catch (const YAML::Exception& e) {
    diag.error(e.mark, "", "YAML syntax error: " + e.msg);
  }
  if (!diag.messages.empty()) throw SpecError(diag.sorted_messages());
  ExperimentSpec spec;
  spec.source_path = source_name;
  spec.source_hash = sha256_hex(yaml_text);
  spec.base_dir = base_dir;
  if (!root.IsMap()) {
    diag.error(root, "",
               "a spec is a map of keys (crowdlab, name, factors, ...), got " + describe_node(root));
    throw SpecError(diag.sorted_messages());
  }
  YamlSection top(diag, root, "");
  top.allow_keys({"crowdlab", "name", "description", "seed", "scenario", "crowd", "animation", "correction",
                  "render", "factors", "repetitions", "duration_s", "fps", "resolution", "protocol",
                  "outputs"});
  top.integer("crowdlab", spec.format_version, kFormatVersion, kFormatVersion);
  if (top.require("name")) top.string("name", spec.name);
  if (top.has("name") && spec.name.empty()) diag.error(top.get("name"), "name", "must not be empty");
  if (const std::string bad = describe_control_character(spec.name); !bad.empty())
    diag.error(top.get("name"), "name",
               "holds " + bad + "; a name is printed in terminals and written into job scripts");
  top.string("description", spec.description);
  top.seed("seed", spec.seed);
  parse_scenario(top.section("scenario"), spec);
  parse_crowd(top.section("crowd"), spec);
  parse_animation(top.section("animation"), spec);
  parse_correction(top.section("correction"), spec);
  parse_render(top.section("render"), spec);
  parse_factors(top, spec);
  top.integer("repetitions", spec.repetitions, 1, 1000);
  top.number("duration_s", spec.duration_s, Range::positive(3600.0));
  top.number("fps", spec.fps, Range::positive(240.0));
  parse_resolution(top, spec);
  parse_protocol(top.section("protocol"), spec);
  parse_outputs(top.section("outputs"), spec);
  check_consistency(top, spec);
  check_work_limits(top, spec);
  if (!diag.messages.empty()) throw SpecError(diag.sorted_messages());
  return spec;
}

ExperimentSpec load_experiment_spec(const std::string& path) {
  // A FIFO would block for ever and /dev/zero never ends (issue 32): refused before opening; a spec is a
  // few kB, so its size is checked before it is read.
  if (!std::filesystem::exists(path))
    throw InputError(SourceLocation{path, 0, 0, ""}, "cannot open the spec file: no such file");
  const std::string text = read_regular_file(path, "the spec", kMaxSpecBytes, "nothing: a spec is a few kB");
  const std::string base = std::filesystem::path(path).parent_path().string();
  // A library's exception the key checks miss (an allocation, a JSON type in an asset the spec names)
  // names the spec (issue 33).
  return at_input_boundary(path,
                           [&] { return load_experiment_spec_text(text, path, base.empty() ? "." : base); });
}

}  // namespace crowdlab
