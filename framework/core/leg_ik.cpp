#include "framework/core/leg_ik.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/align_two_axes.hpp"
#include "framework/core/capsule.hpp"

namespace crowdlab {

LegJoints leg_joints(LegSide side) {
  return side == LegSide::kLeft ? LegJoints{kLeftHip, kLeftKnee, kLeftAnkle, kLeftFoot}
                                : LegJoints{kRightHip, kRightKnee, kRightAnkle, kRightFoot};
}

double leg_length(const BodyShape& shape, LegSide side) {
  const LegJoints j = leg_joints(side);
  return shape.joint_offsets_m[static_cast<size_t>(j.knee)].norm() +
         shape.joint_offsets_m[static_cast<size_t>(j.ankle)].norm();
}

Vec3 hip_position(const BodyShape& shape, const Pose& pose, LegSide side) {
  const LegJoints j = leg_joints(side);
  return pose.root_position_m +
         pose.local_rotations[kPelvis] * shape.joint_offsets_m[static_cast<size_t>(j.hip)];
}

Vec3 ankle_from_ball(const BodyShape& shape, LegSide side, const Vec3& ball, const Quat& foot_rotation) {
  return ball - foot_rotation * shape.joint_offsets_m[static_cast<size_t>(leg_joints(side).foot)];
}

double solve_leg_ik(const BodyShape& shape, Pose& pose, LegSide side, const Vec3& ankle_target,
                    const Quat& foot_rotation, const Vec3& knee_pole) {
  const LegJoints j = leg_joints(side);
  const Vec3 off_knee = shape.joint_offsets_m[static_cast<size_t>(j.knee)];
  const Vec3 off_ankle = shape.joint_offsets_m[static_cast<size_t>(j.ankle)];
  const double l1 = off_knee.norm(), l2 = off_ankle.norm();
  const Quat pelvis = pose.local_rotations[kPelvis];
  const Vec3 hip = hip_position(shape, pose, side);

  Vec3 to_target = ankle_target - hip;
  double d = to_target.norm();
  const Vec3 u = d > 1e-9 ? Vec3(to_target / d) : Vec3(-Vec3::UnitY());
  const double d_clamped = std::clamp(d, std::abs(l1 - l2) + 1e-9, l1 + l2 - 1e-9);
  const double error = std::abs(d - d_clamped);
  d = d_clamped;

  // Bend direction: the pole made perpendicular to the hip-ankle line.
  Vec3 w = knee_pole - knee_pole.dot(u) * u;
  if (w.norm() < 1e-9) w = any_perpendicular(u);
  w.normalize();
  const double cos_a = std::clamp((l1 * l1 + d * d - l2 * l2) / (2.0 * l1 * d), -1.0, 1.0);
  const double sin_a = std::sqrt(1.0 - cos_a * cos_a);
  const Vec3 knee = hip + l1 * (cos_a * u + sin_a * w);
  const Vec3 ankle = hip + d * u;

  // World rotations of thigh and shank: bone direction exact, rest forward (+Z) toward the pole, so
  // both share the bend-plane normal and the knee is a hinge.
  const Quat thigh = align_two_axes(off_knee, Vec3::UnitZ(), knee - hip, w);
  const Quat shank = align_two_axes(off_ankle, Vec3::UnitZ(), ankle - knee, w);

  pose.local_rotations[static_cast<size_t>(j.hip)] = (pelvis.conjugate() * thigh).normalized();
  pose.local_rotations[static_cast<size_t>(j.knee)] = (thigh.conjugate() * shank).normalized();
  pose.local_rotations[static_cast<size_t>(j.ankle)] = (shank.conjugate() * foot_rotation).normalized();
  return error;
}

double reach_ankle(const BodyShape& shape, Pose& pose, LegSide side, const Vec3& ankle_target,
                   const Quat& foot_rotation) {
  const LegJoints j = leg_joints(side);
  const BoneTransforms bones = forward_kinematics(shape, pose);
  const Vec3 hip = bones[static_cast<size_t>(j.hip)].translation;
  const Vec3 knee = bones[static_cast<size_t>(j.knee)].translation;
  const Vec3 ankle = bones[static_cast<size_t>(j.ankle)].translation;
  Quat thigh = bones[static_cast<size_t>(j.hip)].rotation;
  Quat shank = bones[static_cast<size_t>(j.knee)].rotation;
  const double l1 = (knee - hip).norm(), l2 = (ankle - knee).norm();

  const double d_goal_raw = (ankle_target - hip).norm();
  const double d_goal = std::clamp(d_goal_raw, std::abs(l1 - l2) + 1e-9, l1 + l2 - 1e-9);
  // Knee: the angle beta between thigh and shank directions sets the hip-ankle distance,
  // d^2 = l1^2 + l2^2 + 2 l1 l2 cos(beta). Rotating the shank about n = t x s by +a increases beta.
  const Vec3 t = (knee - hip) / l1, s = (ankle - knee) / l2;
  Vec3 n = t.cross(s);
  if (n.norm() < 1e-9) n = thigh * Vec3::UnitX();  // straight leg: the knee's hinge axis
  n.normalize();
  const double beta_now = std::atan2(t.cross(s).dot(n), t.dot(s));
  const double beta_goal =
      std::acos(std::clamp((d_goal * d_goal - l1 * l1 - l2 * l2) / (2.0 * l1 * l2), -1.0, 1.0));
  const Quat flex(Eigen::AngleAxisd(beta_goal - beta_now, n));
  shank = (flex * shank).normalized();
  const Vec3 ankle_flexed = knee + flex * (ankle - knee);
  // Hip: swing the leg so that the hip-ankle line points at the target.
  const Quat swing = Quat::FromTwoVectors(ankle_flexed - hip, ankle_target - hip);
  thigh = (swing * thigh).normalized();
  shank = (swing * shank).normalized();

  const Quat pelvis = bones[static_cast<size_t>(kJointParent[static_cast<size_t>(j.hip)])].rotation;
  pose.local_rotations[static_cast<size_t>(j.hip)] = (pelvis.conjugate() * thigh).normalized();
  pose.local_rotations[static_cast<size_t>(j.knee)] = (thigh.conjugate() * shank).normalized();
  pose.local_rotations[static_cast<size_t>(j.ankle)] = (shank.conjugate() * foot_rotation).normalized();
  return std::abs(d_goal_raw - d_goal);
}

}  // namespace crowdlab
