#pragma once
// ExperimentSpec: the validated, typed form of one YAML experiment spec (see docs/spec-reference.md).
// Produced once at the boundary by load_experiment_spec(); every later stage reads these plain
// structs and never sees YAML. All fields have defaults, so a spec only names what it changes.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "framework/spec/condition_kinds.hpp"
#include "framework/spec/condition_params.hpp"

namespace crowdlab {

/// A factor level as written in the spec. `text` is the canonical string used in ids and tables
/// ("2.22", "V3", "ours"); `number` is set when the level is numeric.
struct FactorLevel {
  std::string text;
  std::optional<double> number;
};

/// One within-subject factor, e.g. density: [2.22, 3.33, ...]. Known names: density, characters,
/// viewpoint, method, shoulder, distance, trigger, scenario, side.
struct Factor {
  std::string name;
  std::vector<FactorLevel> levels;
};

/// scenario.* : where characters are and how they move (2D). Fields apply per `type`.
struct ScenarioSpec {
  ScenarioKind type = ScenarioKind::stationary;
  double width_m = 3.0;                               ///< area / corridor width (x extent), metres
  double depth_m = 3.0;                               ///< area depth / corridor length (z extent), metres
  double stage_direction_deg = 0.0;                   ///< stationary: direction the crowd faces (0 = +Z)
  double walk_speed_mps = 1.3;                        ///< preferred walking speed, metres/second
  double initial_spacing_m = 1.0;                     ///< flow_a/flow_b: initial distance between agents
  PassingSide passing_side = PassingSide::alternate;  ///< pair_crossing (alternate: by repetition)
  std::string mesh;  ///< manifold: scene name, or mesh file path resolved against the spec folder
  int agents = 0;    ///< manifold/flows: agent count when not set by a factor (0 = derive)
};

/// crowd.* : the 2D navigation model.
struct CrowdSpec {
  CrowdModel model = CrowdModel::orca;
  double agent_radius_m = 0.25;  ///< disc radius, metres, (0, 1]
  double neighbor_distance_m = 2.0;
  int max_neighbors = 10;
  double time_horizon_s = 2.0;
  double obstacle_time_horizon_s = 2.0;
  double max_speed_mps = 1.5;
  double dt_s = 0.1;  ///< simulation step (trajectories are resampled to fps)
  /// ORCA only: the overlap-free mode (OrcaParams::resolve_overlaps; step guards plus the overlap
  /// projection, framework/crowd/orca_model.hpp). Off: plain ORCA as published (residual overlaps in jams).
  bool overlap_free = false;
  /// cost model: goal, smoothness, separation, walls, sigma_m, lookahead_s, iterations (keys and ranges
  /// checked by the spec loader; framework/crowd/cost_gradient_model.hpp)
  std::map<std::string, double> cost_weights;
  /// Initial placement (stationary, corridor): > 0 places centres by plain Poisson-disk dart throwing
  /// at this spacing (metres) wherever it is below the hexagonal spacing of the density, so neighbours
  /// stand at irregular distances from this one up, as people do; 0 spreads them as evenly as the
  /// count allows (framework/crowd/place_poisson_disk.hpp).
  double personal_space_m = 0.0;
};

/// animation.* : bodies and motion.
struct AnimationSpec {
  BodyModel body_model = BodyModel::procedural;
  std::string body_model_path;  ///< mpfb2 asset folder (or env CROWDLAB_MPFB2)
  double female_fraction = 0.5;
  MotionSource motion = MotionSource::procedural;
  std::vector<std::string> walk_clips;       ///< BVH/glTF files, resolved against the spec folder
  std::vector<double> walk_clip_speeds_mps;  ///< one per walk clip, metres/second
  std::vector<std::string> dance_clips;      ///< resolved against the spec folder
  double ttca_threshold_s = 0.7;             ///< shoulder reaction trigger (seed 001 §4.1)
  double dtca_threshold_m = 0.6;
  /// The bodies' collision capsules (issue 27): `volume` fitted to the skin each bone carries (what the
  /// body model builds), `fitted` to the rendered mesh per surface (skin, garments and shoe uppers within
  /// 5 mm, hair 20 mm: framework/body/fit_crowd_proxies.hpp), `auto` fitted for a stationary crowd of MPFB2
  /// bodies and volume otherwise (dense walking flows break down with the larger fitted bodies:
  /// docs/correction.md, "Fitted proxies by default for the concert").
  CollisionProxies collision_proxies = CollisionProxies::automatic;
};

/// correction.* : the collision corrector (seed 000 §3).
struct CorrectionSpec {
  double stiffness = 0.0;            ///< PD spring k; 0 = solver default
  double damping = 0.006;            ///< PD damping d (seed 000 Eq. 4)
  double collision_stiffness = 0.0;  ///< k_delta; 0 = solver default
};

/// render.check.* : the thresholds of the stimulus check that `run` computes for every clip
/// (stimuli/stimulus_check.hpp; issue 28's targets are the defaults). A clip outside them is a warning,
/// or a failure under `run --strict`. Pixel sizes are given for a 1080-pixel-high image and scale with
/// the image height.
struct StimulusCheckSpec {
  double crowd_in_frame_min = 0.95;        ///< share of characters wholly in the image, every frame
  double character_height_px_min = 150.0;  ///< median on-screen character height (px at 1080p)
  double overhead_height_px_min = 60.0;    ///< the same for the overhead viewpoint V4
  double seam_step_ratio_max = 1.5;        ///< looping clips (protocol.loop_video) only
  double baseline_overlap_frames_min =
      0.0;  ///< share of a baseline clip's frames with overlap pixels; 0 = off
  /// The overlap measures render every Nth frame again in overlap mode (0 = skip them); every frame when
  /// render.overlap is on anyway.
  int overlap_every_frames = 10;
};

/// render.* : stimulus rendering.
struct RenderSpec {
  int width = 1920;
  int height = 1080;
  int crf = 18;
  int msaa = 1;  ///< samples per pixel: 1 (the fast path) or 4 (the quality reference), docs/stimuli.md
  bool overlap = false;  ///< paint overlapping volume red (seed 000 Fig. 5)
  bool frames_png = false;
  std::string background = "#d8dde3";
  bool fog = false;
  /// render.viewpoints: explicit cameras replacing catalogue presets (checked by the loader).
  std::map<ViewpointId, CameraPlacement> viewpoint_overrides;
  std::vector<std::string> characters;  ///< skinned glTF character files (resolved); character i uses i mod N
  StimulusCheckSpec check;
};

struct QuestionSpec {
  std::string id;
  std::string text;
  bool reverse = false;             ///< reverse-keyed item: analysed as (k+1) - answer
  std::string kind = "scale";       ///< scale | yesno
  int points = 0;                   ///< 0 = protocol scale
  std::vector<std::string> labels;  ///< anchor labels (first, last) or one per point
};

struct CompositeSpec {
  std::string id;
  std::vector<std::string> items;  ///< question ids averaged after reverse coding
};

/// protocol.* : the study a participant runs.
struct ProtocolSpec {
  ProtocolType type = ProtocolType::likert;
  int scale_points = 6;
  std::vector<std::string> scale_labels;
  std::vector<QuestionSpec> questions;
  std::vector<CompositeSpec> composites;
  /// Practice trials (protocol.practice): the crossing of these levels. Factors not named here take
  /// their first level; when block_by is set and not named here, the practice set is repeated for
  /// every block level (seed 001 §4.2.2: practice "at the beginning of each block").
  std::vector<Factor> practice_factors;
  std::string block_by;  ///< factor whose levels form blocks ("" = one block)
  BlockOrder block_order = BlockOrder::random;
  int break_every = 0;  ///< a break screen every N trials (0 = none)
  std::string instructions;
  std::string consent;
  std::string break_text = "Take a short break.";
  bool loop_video = true;  ///< loop until answered (Likert)
  /// Between trials, while the next clip loads (protocol.inter_trial): blank (background only) or
  /// fixation (a cross where the video will be), shown for at least inter_trial_min_ms.
  InterTrialScreen inter_trial_screen = InterTrialScreen::fixation;
  double inter_trial_min_ms = 500.0;
  /// Minimum viewing time (protocol.min_view_ms): answers before stimulus onset + this are not
  /// accepted. < 0 (the default): the clip's duration (one loop for Likert, the whole clip for 2AFC).
  double min_view_ms = -1.0;
  /// Share of the screen height given to the video (protocol.video_share); 0 = as large as the
  /// questions allow.
  double video_share = 0.0;
  /// Online studies (export-web): where the end screen sends the participant, e.g. a panel's
  /// completion link ("" = no redirect). http(s) only.
  std::string completion_url;
};

/// outputs.* : what `crowdlab run` makes besides the crowds (the analysis report is `crowdlab analyze`'s).
struct OutputSpec {
  bool video = true;          ///< the render stage: one clip per condition
  bool contact_sheet = true;  ///< the contact_sheet stage: V1-V4 at the middle frame per crowd and method
  bool metrics = true;        ///< the metrics stage
};

struct ExperimentSpec {
  std::string source_path;  ///< the YAML file it came from ("<embedded demo>" for the demo)
  std::string source_hash;  ///< sha256 hex of the YAML text (provenance)
  std::string base_dir;     ///< folder of the spec file; relative paths in the spec resolve against it
  int format_version = 1;
  std::string name;
  std::string description;
  std::uint64_t seed = 0;
  ScenarioSpec scenario;
  CrowdSpec crowd;
  AnimationSpec animation;
  CorrectionSpec correction;
  RenderSpec render;
  std::vector<Factor> factors;  ///< in spec order
  int repetitions = 1;
  double duration_s = 10.0;
  double fps = 30.0;
  ProtocolSpec protocol;
  OutputSpec outputs;

  const Factor* factor(const std::string& factor_name) const {
    for (const Factor& f : factors)
      if (f.name == factor_name) return &f;
    return nullptr;
  }
};

/// One cell of the design: a level for every factor, plus the repetition index (1-based). Stages read
/// the typed `params`; the level texts name the condition in ids, file names and response tables.
struct Condition {
  std::string id;                             ///< stable, e.g. "density-2.22_viewpoint-V1_method-ours_rep-1"
  std::map<std::string, FactorLevel> levels;  ///< factor name -> level
  int repetition = 1;
  bool practice = false;
  std::uint64_t seed = 0;  ///< derive_seed(spec.seed, id)
  ConditionParams params;  ///< the levels as typed values (type_condition(), framework/spec)

  const FactorLevel* level(const std::string& factor) const {
    auto it = levels.find(factor);
    return it == levels.end() ? nullptr : &it->second;
  }
  /// Numeric level of `factor`, or `fallback` when the factor is absent.
  double number(const std::string& factor, double fallback) const {
    const FactorLevel* l = level(factor);
    return l && l->number ? *l->number : fallback;
  }
  std::string text(const std::string& factor, const std::string& fallback) const {
    const FactorLevel* l = level(factor);
    return l ? l->text : fallback;
  }
};

}  // namespace crowdlab
