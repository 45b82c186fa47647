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

}  // namespace crowdlab
