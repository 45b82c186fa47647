#include "framework/correction/blend_keeping_planted_feet.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "framework/core/blend_poses.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"

namespace crowdlab {
namespace {

/// lifted[side][k]: the input lifts that foot on frame first + k (neither its ankle nor its ball planted,
/// the corrector's test on the joint's step since the frame before; first >= 1).
std::array<std::vector<bool>, 2> lifted_frames(const CharacterAnimation& in, int first, int window,
                                               double max_step_m, const CorrectorParams& p) {
  std::array<std::vector<bool>, 2> lifted;
  auto before = joint_positions(in.shape, in.frames[static_cast<size_t>(first - 1)]);
  for (int k = 0; k < window; ++k) {
    const auto now = joint_positions(in.shape, in.frames[static_cast<size_t>(first + k)]);
    for (size_t s = 0; s < 2; ++s) {
      const LegJoints leg = leg_joints(kLegSides[s]);
      bool planted = false;
      for (int j : {leg.ankle, leg.foot}) {
        const auto ju = static_cast<size_t>(j);
        planted =
            planted || ((now[ju] - before[ju]).norm() < max_step_m && now[ju].y() < p.foot_plant_height_m);
      }
      lifted[s].push_back(!planted);
    }
    before = now;
  }
  return lifted;
}

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

}  // namespace

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
