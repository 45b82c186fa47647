#include "framework/animation/animate_crowd.hpp"

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "framework/animation/bvh.hpp"
#include "framework/animation/clip_in_place.hpp"
#include "framework/animation/clip_loop.hpp"
#include "framework/animation/dance_animation.hpp"
#include "framework/animation/import_motion_clip.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/animation/sample_bodies.hpp"
#include "framework/animation/shoulder_reactions.hpp"
#include "framework/animation/walk_animation.hpp"
#include "framework/animation/walk_from_clips.hpp"
#include "framework/core/appearance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

namespace {
std::string character_name(size_t i) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "c%03zu", i);
  return buf;
}

// Where a dressed crowd's clothing indices start: drawn from the crowd's seed, so that two crowds of a
// study wear different colour sets (fabric_palette draws each index's colours from its own stream: with
// the indices 0..N-1 every crowd of N wore the same N colour sets in another order, issue 28). The N
// indices stay consecutive, so fabric_palette's evenly spread grey hair keeps its share in every crowd.
int dressed_clothing_offset(std::uint64_t seed, size_t n) {
  Rng rng(derive_seed(seed, "palette/dressed offset"));
  return static_cast<int>(uniform_index(rng, static_cast<size_t>(kAppearanceStride) - n));
}

void check_trajectories(const CrowdTrajectories& t) {
  if (!(t.fps > 0) || !std::isfinite(t.fps)) throw InputError("animate_crowd: trajectories fps must be > 0");
  if (t.agents.empty()) throw InputError("animate_crowd: no agents in the trajectories");
  const size_t frames = t.agents.front().position_m.size();
  if (frames == 0) throw InputError("animate_crowd: trajectories have no frames");
  for (size_t i = 0; i < t.agents.size(); ++i) {
    const AgentTrajectory& a = t.agents[i];
    if (a.position_m.size() != frames || a.heading_rad.size() != frames)
      throw InputError("animate_crowd: agent " + std::to_string(i) + " has " +
                       std::to_string(a.position_m.size()) + " positions and " +
                       std::to_string(a.heading_rad.size()) + " headings, expected " +
                       std::to_string(frames));
  }
}
}  // namespace

CrowdAnimation animate_crowd(const CrowdTrajectories& trajectories, const Environment& environment,
                             const AnimationSpec& spec, const AnimationContext& context) {
  check_trajectories(trajectories);
  const size_t n = trajectories.agents.size();
  const auto frames = static_cast<size_t>(trajectories.frame_count());
  const bool stationary = context.scenario == ScenarioKind::stationary;
  const bool clips = spec.motion == MotionSource::clips;
  if (clips && stationary && spec.dance_clips.empty())
    throw InputError(
        "animation.dance_clips: 'clips' motion in a stationary scenario needs at least one dance clip");
  if (clips && !stationary && spec.walk_clips.empty())
    throw InputError(
        "animation.walk_clips: 'clips' motion in a walking scenario needs at least one walk clip");
  auto import_clip = [&](const std::string& file) {
    const std::filesystem::path path = std::filesystem::path(file).is_absolute()
                                           ? std::filesystem::path(file)
                                           : context.clip_directory / file;
    return import_motion_clip(path);
  };
  std::vector<BvhMotion> dance_clips, walk_clips;
  if (clips && stationary)
    for (const std::string& file : spec.dance_clips) dance_clips.push_back(import_clip(file));
  if (clips && !stationary)
    for (const std::string& file : spec.walk_clips) walk_clips.push_back(import_clip(file));
  if (!context.shapes.empty() && context.shapes.size() != n)
    throw InputError("animate_crowd: " + std::to_string(context.shapes.size()) + " body shapes for " +
                     std::to_string(n) + " agents");
  if (!context.meshes.empty() && context.meshes.size() != context.shapes.size())
    throw InputError("animate_crowd: " + std::to_string(context.meshes.size()) + " body meshes for " +
                     std::to_string(context.shapes.size()) + " body shapes");
  if (!context.skin_tones.empty() && context.skin_tones.size() != context.shapes.size())
    throw InputError("animate_crowd: " + std::to_string(context.skin_tones.size()) + " skin tones for " +
                     std::to_string(context.shapes.size()) + " body shapes");
  for (const int tone : context.skin_tones)
    if (tone < -1 || tone >= kSkinToneCount)
      throw InputError("animate_crowd: skin tone " + std::to_string(tone) + " is not in [-1, " +
                       std::to_string(kSkinToneCount - 1) + "]");
  if (context.shapes.empty() && spec.body_model != BodyModel::procedural)
    throw InputError("animation.body_model: '" + std::string(kind_name(spec.body_model)) +
                     "' needs its shapes passed in AnimationContext::shapes");

  std::vector<BodyShape> shapes = context.shapes;
  if (shapes.empty()) {
    const std::vector<BodyParams> params =
        sample_bodies(static_cast<int>(n), spec.female_fraction, derive_seed(context.seed, "bodies"));
    shapes.resize(n);
    for (size_t i = 0; i < n; ++i) shapes[i] = make_procedural_body(params[i]);
  }

  ShoulderReactions reactions;
  if (!stationary && (context.trigger_probability > 0.0 || context.shoulder_count >= 0)) {
    ShoulderReactionParams rp;
    rp.ttca_threshold_s = spec.ttca_threshold_s;
    rp.dtca_threshold_m = spec.dtca_threshold_m;
    rp.trigger_probability = context.trigger_probability;
    rp.forced_count = context.shoulder_count;
    reactions = compute_shoulder_reactions(trajectories, rp, derive_seed(context.seed, "shoulder"));
  }

  // Seeded palette permutation.
  std::vector<int> palette(n);
  std::iota(palette.begin(), palette.end(), 0);
  Rng prng(derive_seed(context.seed, "palette"));
  for (size_t i = n; i > 1; --i) std::swap(palette[i - 1], palette[uniform_index(prng, i)]);
  const int dressed_offset = context.skin_tones.empty() ? 0 : dressed_clothing_offset(context.seed, n);

  CrowdAnimation crowd;
  crowd.environment = environment;
  crowd.meta.fps = trajectories.fps;
  crowd.meta.seed = context.seed;
  crowd.meta.condition_id = context.condition_id;
  crowd.meta.scenario = kind_name(context.scenario);
  crowd.characters.resize(n);
  const double duration = static_cast<double>(frames) / trajectories.fps;
  tbb::parallel_for(size_t{0}, n, [&](size_t i) {
    CharacterAnimation& c = crowd.characters[i];
    c.name = character_name(i);
    c.shape = shapes[i];
    c.palette = palette[i];
    if (!context.meshes.empty()) c.mesh = context.meshes[i];
    if (!context.skin_tones.empty())
      c.palette = pack_appearance(dressed_offset + palette[i], context.skin_tones[i]);
    const std::uint64_t cseed = derive_seed(context.seed, "character/" + c.name);
    if (clips && !stationary) {
      // Each walk clip's gait cycle on this body (retargeting scales to its proportions).
      std::vector<WalkCycle> cycles;
      for (size_t k = 0; k < walk_clips.size(); ++k) {
        cycles.push_back(
            extract_walk_cycle(retarget_bvh(walk_clips[k], c.shape), c.shape, walk_clips[k].source));
        const double named = k < spec.walk_clip_speeds_mps.size() ? spec.walk_clip_speeds_mps[k] : 0.0;
        if (i == 0 && named > 0.0 && std::abs(cycles.back().speed_mps / named - 1.0) > 0.3)
          spdlog::warn(
              "{}: walks at {:.2f} m/s on {}, not the {:.2f} m/s the spec names; using the measured speed",
              walk_clips[k].source, cycles.back().speed_mps, c.name, named);
      }
      const std::vector<double> none;
      c.frames = animate_walking_from_clips(c.shape, cycles, trajectories.agents[i], trajectories.fps,
                                            walk_style_from_seed(cseed).phase0,
                                            reactions.weight.empty() ? none : reactions.weight[i])
                     .frames;
    } else if (clips) {
      Rng rng(derive_seed(cseed, "clip"));
      const BvhMotion& clip = dance_clips[uniform_index(rng, dance_clips.size())];
      const RetargetedClip r = retarget_bvh(clip, c.shape);
      const int n_src = static_cast<int>(r.frames.size());
      const int blend = std::min(15, n_src / 4);
      if (n_src < 8)
        throw InputError(clip.source + ": clip too short to loop (" + std::to_string(n_src) + " frames)");
      const LoopedClip loop = make_seamless_loop(r.frames, blend, n_src, blend);
      const double loop_s = static_cast<double>(loop.frames.size()) / r.fps;
      c.frames =
          play_clip_in_place(loop, r.fps, trajectories.agents[i], trajectories.fps, uniform01(rng) * loop_s);
    } else if (stationary) {
      c.frames = animate_dancing(c.shape, trajectories.agents[i], trajectories.fps,
                                 dance_style_from_seed(cseed, duration))
                     .frames;
    } else {
      const std::vector<double> none;
      c.frames =
          animate_walking(c.shape, trajectories.agents[i], trajectories.fps, walk_style_from_seed(cseed),
                          reactions.weight.empty() ? none : reactions.weight[i])
              .frames;
    }
  });
  validate_crowd(crowd, "animate_crowd(" + context.condition_id + ")");
  return crowd;
}

}  // namespace crowdlab
