#pragma once
// The recipes of a crowd group's four stages (crowd_group.hpp), issue 30: plain structs holding exactly
// the spec values and parameters each stage's computation reads, built from the typed spec in one place
// (crowd_group_recipes()). A stage's input hash is its recipe's canonical bytes (stage.hpp), so a value
// outside its recipe (the protocol's wording, the render settings, the YAML's comments) never redoes it,
// and a value inside it always does. Adding a value a stage reads is one line: a field here, filled in
// crowd_group_recipes().
//   recipe           stage        read by
//   CrowdRecipe      crowd        generate_scenario / generate_manifold_scenario (via recipe_spec())
//   AnimationRecipe  animation    animate_scenario (animate_scenario.hpp)
//   CorrectionRecipe correction   correct_crowd (framework/correction)
//   MetricsRecipe    metrics      measure_crowd, measure_correction_quality (framework/metrics)
// Files a stage reads are its inputs, hashed by content (Stage::inputs): the manifold mesh file of the
// crowd stage, the motion clips of the animation stage, the crowd files of the later stages.
// Units: metres, seconds, frames per second, as in experiment_spec.hpp.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "framework/correction/corrector_params.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// The crowd stage: where the characters are and how they move (trajectories.csv).
struct CrowdRecipe {
  static constexpr std::string_view kStage = "crowd";
  /// 2: stationary sway and look-around loop over the clip, personal-space placement (issue 28). 3: a
  /// personal space the dart throwing cannot hold is relaxed back to it (place_poisson_disk.hpp; issue 28,
  /// session 24).
  static constexpr std::string_view kCodeVersion = "3";
  ScenarioSpec scenario;  ///< only the fields the condition's scenario kind reads (others at defaults)
  CrowdSpec crowd;        ///< likewise: the navigation model's fields only for kinds that simulate
  double duration_s = 10.0;
  double fps = 30.0;
  /// The group's levels the generators read (kind, size, the pair's distance and side); the others stay at
  /// their defaults, since every viewpoint and method of a group shows this crowd (crowd_key.hpp).
  ConditionParams params;
  std::uint64_t seed = 0;  ///< the group's seed (crowd_condition())
};

/// The animation stage: full-body motion on the crowd's trajectories (baseline.glb).
struct AnimationRecipe {
  static constexpr std::string_view kStage = "animation";
  /// 2: dressed bodies, the new stage (issue 28); 3: fingers side by side, skin under hems tucked (issue 28,
  /// session 12); 4: dressed crowds' clothing indices start at a seeded offset (other colours per crowd);
  /// 5: the collision capsules as animation.collision_proxies says, resolved (fitted for a stationary crowd
  /// of MPFB2 bodies; issue 27, session 25).
  static constexpr std::string_view kCodeVersion = "5";
  AnimationSpec animation;  ///< body_model_path only with MPFB2 bodies (empty for procedural ones)
  ScenarioKind scenario = ScenarioKind::stationary;  ///< stationary: dancing; otherwise walking
  std::optional<int> shoulder_count;                 ///< `shoulder` factor
  double trigger_probability = 0.0;                  ///< `trigger` factor / 100
  std::uint64_t seed = 0;                            ///< the group's seed
  std::string key;                                   ///< crowd key, recorded in the crowd file
};

/// Loop closure window of looping clips (s): four whole laps of the clip are run before frame 0, and the
/// clip's last 2 s blend into the last lap's (correct_crowd.hpp). 2 s is about two dance steps at the
/// concert's tempi, so most feet lift inside the window and can move to the pre-roll's spots while they swing
/// (blend_keeping_planted_feet.hpp).
inline constexpr double kLoopPrerollS = 2.0;
/// Shortest looping clip that gets the pre-roll (s). Its window is half the clip up to kLoopPrerollS
/// (loop_preroll_window_s). On a clip shorter than 2 s the closing blend would rewrite most of it toward a
/// second correction of itself, which edits limbs that touch nobody: on `reproduce gomez2024 --quick`'s
/// 1 s clips a free wrist ended 6.9 deg off its input at 5.55/m^2 (issue 27's limit: 5). Such clips stay
/// open (issue 28: or not looped). Session 26 lowered it from 4 s (twice the full window): the demo's 2 s
/// clips, left open, looped with a seam of 2.0-2.6x the median frame step (every `ours` clip warned);
/// closed over 1 s they loop at 1.01-1.09x, with free limbs within 2.0 deg and p99 capsule depths of
/// 4.9 / 17.5 mm at 3.33 / 6.66 /m^2 (docs/stimuli.md, "Session 26").
inline constexpr double kLoopPrerollMinClipS = 2.0;

/// The loop pre-roll window of a looping clip of `duration_s` (s): kLoopPrerollS, or half the clip when
/// that is shorter; 0 below kLoopPrerollMinClipS.
double loop_preroll_window_s(double duration_s);

/// The correction stage: the collision corrector on baseline.glb (ours.glb).
struct CorrectionRecipe {
  static constexpr std::string_view kStage = "correction";
  /// 2: issue 27's free joints; 3: barrier rows in the depenetration pass, planted feet held in height and
  /// returning their tilt (issue 27, session 10); 4: the loop pre-roll on for looping clips, its closure
  /// keeping planted feet (issue 28, session 11; clips of at least 4 s); 5: knees of held legs flex about
  /// their hinge when nearly straight and turn about the shank at most at the light-joint rate (issue 27,
  /// session 11); 6: the loop pre-roll is two whole laps of the clip, and a closure too deep for all
  /// characters closes some (issue 28, session 12); 7: four laps; inside the re-corrected closure, feet the
  /// input plants stay where they stood before it set them down and arms aim at the input; characters it
  /// leaves too deep try the plain blend (issue 28, session 13); 8: engaged elbows rate-limited as the
  /// light joints (issue 27, session 13); 9: the depenetration pass never pushes a capsule into an
  /// environment box or a foot below the ground (surface guards), and held feet give way when their lower leg
  /// is deep in a box (issue 27, session 15); 10: characters a too-deep closure leaves open may start from
  /// the next lap, close their arms alone, or close together with their open neighbours, and a closure may
  /// reach 10 mm (issue 28, session 15); 11: engaged necks, heads, collars and shoulders rate-limited too
  /// (issue 27, session 15); 12: engaged knees turn off their hinge at most at that rate, in the step and
  /// the pass (issue 27, session 16); 13: characters still open may take their arms from the next lap up to
  /// a cut inside the clip (issue 28, session 16); 15: knees at lift-off (lift_off_knees) on: a foot held
  /// at its ball with its knee far off the input's pivots about the ball (issue 27, session 18). (Session
  /// 19's held-ankle twist row, held_ankle_twist_in_pass, is off by default: the outputs are version 15's.)
  /// 16: clips under 30 fps corrected in substeps of at most 1/30 s (CorrectorParams::max_step_s; issue
  /// 27, session 26; 30 fps clips unchanged); 17: a whole-crowd loop closure only if it adds no joint flips
  /// to any character, else the per-character choice (issue 28, session 26); 18: crowds that walk on the
  /// flat ground corrected twice, the second time toward their input moved onto the first correction's
  /// roots (follow_root_smoothing_s; issue 27, session 27; standing crowds unchanged), and with their planted
  /// feet kept on the input's ground (`walking`, walking_correction).
  static constexpr std::string_view kCodeVersion = "18";
  CorrectionSpec correction;
  /// Seconds of the clip's end run before frame 0 so that a looping clip loops without a seam
  /// (correct_crowd.hpp; issue 28): loop_preroll_window_s(duration) when protocol.loop_video, else 0.
  double loop_preroll_s = 0.0;
  /// Whether the crowd walks on the flat ground (walks_on_flat_ground): its correction then follows the
  /// pushed roots and keeps planted feet on the input's ground (walking_correction).
  bool walking = false;
};

/// The smoothing (s) of the root offsets a walking crowd's second correction follows
/// (follow_root_offsets.hpp). Measured on the corridor at 6.66 /m^2 following the whole offset (5 s,
/// docs/correction.md, session 27): 0.15 / 0.3 / 0.5 / 1.0 s gave 258 / 253 / 377 / 393 flip joint-frames,
/// one run each (one correction: 323; the clip is chaotic: three runs at 0.3 s gave 159-277, three of one
/// correction 323-339); at 20 s, 0.15 s let planted feet slide (stance drift p99 20-21 mm).
inline constexpr double kWalkingFollowRootS = 0.3;
/// Whether a crowd of `scenario` walks on the flat ground (corridor, flows, crossing pairs): not a standing
/// crowd, not one on a surface.
bool walks_on_flat_ground(ScenarioKind scenario);
/// Sets in `params` the corrector settings of a crowd that walks on the flat ground (session 27). `run` (when
/// the correction recipe says `walking`), `correct` (from the crowd file's scenario) and `experiment
/// overlap-vs-density` all use it:
///   follow_root_smoothing_s = kWalkingFollowRootS: the second correction follows the pushed roots;
///   held_feet_at_input_height and feet_above_input_ground: planted feet on the input's ground. Off for
///   standing crowds, where they deepen the contacts (corrector_params.hpp); on the corridor, following
///   the roots, at 20 s and three runs per density (docs/correction.md, session 27): float p99 33-37 ->
///   21 mm and feet below the ground 18-24 -> 5.9 mm at 6.66 /m^2, 17.5 -> 9.9 mm and 6-6.5 -> 6.3-6.7 mm
///   at 2.22 /m^2, flips 1,736-2,285 -> 1,498-1,661 at 6.66 /m^2.
void walking_correction(CorrectorParams& params);

/// The metrics stage of one method's crowd file (<method>.metrics.json).
struct MetricsRecipe {
  static constexpr std::string_view kStage = "metrics";
  /// 2: free limbs, flips, environment; 3: mesh-level overlap and proxy coverage (issue 27); 5: the feet's
  /// ground penetration added by the correction, below min(0, the input's foot) (issue 27, session 16); 6:
  /// the mesh-level inside test confirms its sign by a ray (surfaces_inside.hpp; issue 27, session 25); 7:
  /// the feet's depth below the ground discounts the capsules' reach below the rendered floor at rest; 8:
  /// the flip window is 0.1 s at 200 deg/s, not 3 frames (core/joint_flips.hpp; session 26; 30 fps
  /// unchanged); 9: looping clips' free-limb window wraps around the loop (free_limb_deviation.hpp; session
  /// 28); 10: and so does their flip window (core/joint_flips.hpp)
  static constexpr std::string_view kCodeVersion = "10";
  CrowdMethod method = CrowdMethod::baseline;  ///< the animation measured (against the baseline)
  bool surface_ground = false;  ///< manifold crowds: the feet's ground is the surface, not y = 0
  bool mesh_measures = true;    ///< the mesh-level overlap and proxy coverage (RunOptions::mesh_measures)
  bool looped = false;          ///< the clips loop (protocol.loop_video): free-limb and flip windows wrap
};

/// Every recipe of one crowd group, and the files its stages read besides the crowd files.
struct CrowdGroupRecipes {
  CrowdRecipe crowd;
  AnimationRecipe animation;
  CorrectionRecipe correction;
  std::vector<std::filesystem::path> crowd_files;      ///< the manifold mesh file, when it is one
  std::vector<std::filesystem::path> animation_files;  ///< walk and dance clips
  std::string source_path;    ///< the spec file, named in error messages only (not hashed)
  bool mesh_measures = true;  ///< RunOptions::mesh_measures, for the metrics recipes
  bool clips_loop = false;    ///< protocol.loop_video, for the metrics recipes
};

/// The recipes of the group whose first condition is `first` (crowd_condition() gives its seed).
CrowdGroupRecipes crowd_group_recipes(const ExperimentSpec& spec, const Condition& first);

/// The metrics recipe of `method`'s crowd file in a group, from the group's recipes (their crowd,
/// mesh_measures and clips_loop), so no caller can build a recipe that differs from the stage's.
MetricsRecipe metrics_recipe(const CrowdGroupRecipes& group, CrowdMethod method);

/// What the scenario generators see: a spec holding only the recipe's values (every other section at
/// its defaults), so they cannot read anything the crowd stage's hash does not cover. `source_path`
/// names the spec in their error messages.
ExperimentSpec recipe_spec(const CrowdRecipe& recipe, const std::string& source_path);
/// The group's condition as the generators see it: the recipe's levels and seed.
Condition recipe_condition(const CrowdRecipe& recipe);

}  // namespace crowdlab
