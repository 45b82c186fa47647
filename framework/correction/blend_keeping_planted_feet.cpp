#include "framework/correction/blend_keeping_planted_feet.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "framework/core/blend_poses.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/input_foot_lifts.hpp"

namespace crowdlab {
namespace {

/// Per leg, the weight of the targets on each window frame: rises (raised cosine) over the frames the
/// foot is lifted, constant while it stands; 0 throughout for a foot that never lifts.
std::vector<double> leg_weights(const std::vector<bool>& lifted) {
  int total = 0;
  for (bool l : lifted) total += l ? 1 : 0;
  std::vector<double> w(lifted.size(), 0.0);
  int seen = 0;
  for (size_t k = 0; k < lifted.size() && total > 0; ++k) {
    seen += lifted[k] ? 1 : 0;
    w[k] = raised_cosine(seen, total);
  }
  return w;
}

/// Lowers the pelvis until both ankle goals are within the legs' reach: a blended body can stand a few
/// centimetres farther from a kept foot than the straight leg is long, and the IK would then leave the
/// foot short of its spot (it slid up to 0.8 mm on a 3.6 cm blend in the test). Only downward and only
/// as far as needed, as the corrector's foot holds do (stage_foot_holds.cpp); a goal farther sideways
/// than the leg is long is left to the IK's clamp.
void lower_pelvis_to_reach(const BodyShape& shape, const std::array<Vec3, 2>& goals, Pose& pose) {
  constexpr double kMargin_m = 1e-7;  // the IK's clamp would otherwise bite
  for (size_t s = 0; s < 2; ++s) {
    const Vec3 to_hip = hip_position(shape, pose, kLegSides[s]) - goals[s];
    const double reach = leg_length(shape, kLegSides[s]) - kMargin_m;
    const double horizontal2 = to_hip.x() * to_hip.x() + to_hip.z() * to_hip.z();
    if (to_hip.norm() <= reach || horizontal2 >= reach * reach) continue;
    pose.root_position_m.y() -= to_hip.y() - std::sqrt(reach * reach - horizontal2);
  }
}

void blend_character(const CharacterAnimation& in, const std::vector<Pose>& targets, int window,
                     const CorrectorParams& p, double max_step_m, CharacterAnimation& clip) {
  const int frames = static_cast<int>(clip.frames.size()), first = frames - window;
  const size_t offset = targets.size() - static_cast<size_t>(window);
  const auto lifted = lifted_frames(in, first, window, max_step_m, p);
  const std::array<std::vector<double>, 2> leg_w = {leg_weights(lifted[0]), leg_weights(lifted[1])};
  for (int k = 0; k < window; ++k) {
    Pose& pose = clip.frames[static_cast<size_t>(first + k)];
    const Pose& target = targets[offset + static_cast<size_t>(k)];
    const BoneTransforms from = forward_kinematics(clip.shape, pose);
    const BoneTransforms to = forward_kinematics(clip.shape, target);
    Pose blended = blend_poses(pose, target, raised_cosine(k + 1, window));
    std::array<Vec3, 2> goals;
    std::array<Quat, 2> turns;
    for (size_t s = 0; s < 2; ++s) {
      const double w = leg_w[s][static_cast<size_t>(k)];
      const auto ankle = static_cast<size_t>(leg_joints(kLegSides[s]).ankle);
      goals[s] = (1.0 - w) * from[ankle].translation + w * to[ankle].translation;
      turns[s] = from[ankle].rotation.slerp(w, to[ankle].rotation).normalized();
    }
    lower_pelvis_to_reach(clip.shape, goals, blended);
    for (size_t s = 0; s < 2; ++s) reach_ankle(clip.shape, blended, kLegSides[s], goals[s], turns[s]);
    pose = blended;
  }
}

/// The inverse of a rigid transform.
RigidTransform inverse(const RigidTransform& t) {
  const Quat r = t.rotation.conjugate();
  return {r, -(r * t.translation)};
}

/// The ankle bone's world transform on frame f of a character.
RigidTransform ankle_transform(const CharacterAnimation& a, int f, size_t ankle) {
  return forward_kinematics(a.shape, a.frames[static_cast<size_t>(f)])[ankle];
}

/// planted[f - first + 1] for f in [first - 1, frames): the input plants the foot on frame f (its ankle or
/// its ball, by the corrector's test on the step since f - 1; first >= 2).
std::vector<bool> planted_frames(const CharacterAnimation& in, int first, size_t s, double max_step_m,
                                 const CorrectorParams& p) {
  const int frames = static_cast<int>(in.frames.size());
  const auto lifted = lifted_frames(in, first - 1, frames - first + 1, max_step_m, p);
  std::vector<bool> planted;
  for (bool l : lifted[s]) planted.push_back(!l);
  return planted;
}

/// One leg's foot goals (world ankle transforms) on frames [first, frames) of `clip` (first >= 2): on a frame
/// where the input plants the foot, the clip's foot as it stood on the frame before the input set it down,
/// moved since then exactly as the input's foot moved (so every point the input keeps still stays still);
/// on a lifted frame, the clip's foot plus what it was last moved by, returning to the clip's foot over the
/// lifted frames of that swing (raised cosine), or kept to the window's end when no swing follows.
std::vector<RigidTransform> planted_foot_goals(const CharacterAnimation& in, const CharacterAnimation& clip,
                                               int first, size_t s, double max_step_m,
                                               const CorrectorParams& p) {
  const int frames = static_cast<int>(clip.frames.size());
  const auto ankle = static_cast<size_t>(leg_joints(kLegSides[s]).ankle);
  const std::vector<bool> planted = planted_frames(in, first, s, max_step_m, p);
  const auto is_planted = [&](int f) {
    return static_cast<bool>(planted[static_cast<size_t>(f - first + 1)]);
  };
  std::vector<RigidTransform> goals;
  RigidTransform input_to_clip;  // the clip's foot in the input foot's frame, on the frame before touch-down
  RigidTransform moved_by;       // goal relative to the clip's foot on the last planted frame
  bool standing = false;
  for (int f = first; f < frames; ++f) {
    const RigidTransform own = ankle_transform(clip, f, ankle);
    if (!is_planted(f)) {
      standing = false;
      int swing = 0, done = 0;
      for (int g = f; g < frames && !is_planted(g); ++g) ++swing;
      for (int g = f - 1; g >= first && !is_planted(g); --g) ++done;
      // Kept to the window's end when the swing does not finish in it: the loop's frame 0 follows.
      const double keep = f + swing >= frames ? 1.0 : 1.0 - raised_cosine(done + 1, done + swing);
      goals.push_back({Quat::Identity().slerp(keep, moved_by.rotation).normalized() * own.rotation,
                       own.translation + keep * moved_by.translation});
      continue;
    }
    if (!standing) {
      const RigidTransform before = f - 1 < first ? ankle_transform(clip, f - 1, ankle) : goals.back();
      input_to_clip = inverse(ankle_transform(in, f - 1, ankle)) * before;
      standing = true;
    }
    const RigidTransform goal = ankle_transform(in, f, ankle) * input_to_clip;
    moved_by = {goal.rotation * own.rotation.conjugate(), goal.translation - own.translation};
    goals.push_back(goal);
  }
  return goals;
}

}  // namespace

void keep_planted_feet_planted(const CrowdAnimation& input, int window, const CorrectorParams& params,
                               CrowdAnimation& clip) {
  if (window <= 0) return;
  const double max_step_m = params.foot_plant_speed_mps / input.meta.fps;
  for (size_t c = 0; c < clip.characters.size(); ++c) {
    CharacterAnimation& ch = clip.characters[c];
    const int frames = static_cast<int>(ch.frames.size()), first = std::max(2, frames - window);
    std::array<std::vector<RigidTransform>, 2> goals;
    for (size_t s = 0; s < 2; ++s)
      goals[s] = planted_foot_goals(input.characters[c], ch, first, s, max_step_m, params);
    for (int f = first; f < frames; ++f) {
      Pose& pose = ch.frames[static_cast<size_t>(f)];
      const size_t k = static_cast<size_t>(f - first);
      lower_pelvis_to_reach(ch.shape, {goals[0][k].translation, goals[1][k].translation}, pose);
      for (size_t s = 0; s < 2; ++s)
        reach_ankle(ch.shape, pose, kLegSides[s], goals[s][k].translation, goals[s][k].rotation);
    }
  }
}

double raised_cosine(int k, int len) {
  if (k >= len) return 1.0;
  return 0.5 - 0.5 * std::cos(std::numbers::pi * k / len);
}

void blend_keeping_planted_feet(const CrowdAnimation& input, const std::vector<std::vector<Pose>>& targets,
                                int window, const CorrectorParams& params, CrowdAnimation& clip) {
  if (window <= 0) return;
  const double max_step_m = params.foot_plant_speed_mps / input.meta.fps;
  for (size_t c = 0; c < clip.characters.size(); ++c)
    blend_character(input.characters[c], targets[c], window, params, max_step_m, clip.characters[c]);
}

}  // namespace crowdlab
