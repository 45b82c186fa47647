#pragma once
// The animation stage's entry point: 2D crowd trajectories -> full-body CrowdAnimation.
//
// Every character is animated independently of its neighbours (as production crowd pipelines do,
// which is what leaves residual collisions for the correction stage):
//   - bodies: sample_bodies(N, spec.female_fraction, derive_seed(seed, "bodies")) -> procedural
//     bodies, unless the context supplies ready-made shapes (e.g. the MPFB2 body model);
//   - scenario "stationary": dancing / idling in place (dance_animation.hpp), one seeded style per
//     character, tempo fitted so the whole clip loops;
//   - "stationary" with animation.motion = "clips": the spec's dance_clips (.bvh, or .gltf/.glb skinned
//     animations; relative paths
//     are taken from AnimationContext::clip_directory) are imported once, retargeted onto each
//     character's body, looped seamlessly and played in place from a seeded start time
//     (clip_in_place.hpp);
//   - walking scenarios with animation.motion = "clips": the spec's walk_clips are imported once; per
//     character each is retargeted onto its body and cut to one seamless gait cycle, and the cycles are
//     blended by speed along the trajectory with planted feet (walk_from_clips.hpp);
//   - any other scenario: procedural walking along the trajectory (walk_animation.hpp) with shoulder
//     reactions (shoulder_reactions.hpp) when trigger_probability > 0 or shoulder_count >= 0.
// Characters are named "c000", "c001", ... in trajectory order; palette = a seeded permutation of
// 0..N-1 (renderers take it modulo their palette count), so neighbours rarely share clothing. With skin
// tones (dressed MPFB2 bodies) the permutation is shifted by a seeded offset in [0, 2^16 - N), so each
// crowd draws its own garment and hair colours (stimuli/fabric_palette.hpp).
// Characters are processed in parallel (TBB) into per-index slots: identical output for any thread
// count. The result passes validate_crowd().
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

struct AnimationContext {
  ScenarioKind scenario = ScenarioKind::stationary;  ///< stationary -> dancing, anything else -> walking
  std::uint64_t seed = 0;                            ///< the condition seed
  int shoulder_count = -1;                           ///< >= 0: exactly this many characters react (pairs)
  double trigger_probability = 0.0;                  ///< per-event shoulder reaction probability
  std::string condition_id;
  std::vector<BodyShape> shapes;  ///< optional: one shape per agent (overrides sampling)
  /// optional (only with `shapes`): one skinned surface per agent, bound to that agent's shape (e.g. the
  /// shaped MPFB2 mesh); copied into CharacterAnimation::mesh for renderers and crowd files
  std::vector<std::shared_ptr<const SkinnedMesh>> meshes;
  /// optional (only with `shapes`): one skin tone per agent, packed into CharacterAnimation::palette with
  /// the clothing palette (core/appearance.hpp)
  std::vector<int> skin_tones;
  std::filesystem::path clip_directory;  ///< base for relative clip paths (the spec file's folder)
};

/// Throws InputError for empty / inconsistent trajectories, a shapes or meshes list of the wrong size or an
/// unsupported animation.body_model / animation.motion.
CrowdAnimation animate_crowd(const CrowdTrajectories& trajectories, const Environment& environment,
                             const AnimationSpec& spec, const AnimationContext& context);

}  // namespace crowdlab
