#include "framework/animation/reaction_pose.hpp"

#include <algorithm>
#include <cmath>

#include "framework/animation/rotation_helpers.hpp"

namespace crowdlab::anim {

namespace {
constexpr double kDeg = kPi / 180.0;
void pre_rotate(Pose& pose, int joint, const Quat& q) {
  auto& r = pose.local_rotations[static_cast<size_t>(joint)];
  r = (q * r).normalized();
}
void post_rotate(Pose& pose, int joint, const Quat& q) {
  auto& r = pose.local_rotations[static_cast<size_t>(joint)];
  r = (r * q).normalized();
}
}  // namespace

double reaction_arm_swing_factor(double weight) {
  return 1.0 - 0.7 * std::min(1.0, std::abs(weight));
}

void apply_reaction_upper_body(Pose& pose, double weight) {
  const double w = std::clamp(weight, -1.0, 1.0);
  if (w == 0.0) return;
  // Trunk: yaw > 0 turns the chest toward +X (left).
  post_rotate(pose, kPelvis, yaw(w * 5.0 * kDeg));
  pre_rotate(pose, kSpine1, yaw(w * 6.0 * kDeg));
  pre_rotate(pose, kSpine2, yaw(w * 9.0 * kDeg));
  pre_rotate(pose, kSpine3, yaw(w * 15.0 * kDeg));
  pre_rotate(pose, kNeck, yaw(-w * 10.0 * kDeg));
  pre_rotate(pose, kHead, yaw(-w * 12.0 * kDeg));
  // Passing-side collar retracts (its shoulder goes back), passing-side arm trails.
  const double a = std::abs(w);
  if (w > 0) {
    pre_rotate(pose, kLeftCollar, yaw(a * 10.0 * kDeg));
    pre_rotate(pose, kLeftShoulder, pitch(a * 12.0 * kDeg));  // pitch > 0 swings a hanging arm backward
  } else {
    pre_rotate(pose, kRightCollar, yaw(-a * 10.0 * kDeg));
    pre_rotate(pose, kRightShoulder, pitch(a * 12.0 * kDeg));
  }
}

}  // namespace crowdlab::anim
