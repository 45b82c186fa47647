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

namespace {
/// Legs bent less than this (sin of the angle) take the knee's anatomical hinge as their bend axis.
constexpr double kStraightLegSin = 0.17;  // about 10 deg
/// A knee bent backward by less than this flexes forward when the leg must get shorter.
constexpr double kHyperextension_rad = 0.09;  // about 5 deg

/// The axis the knee flexes about: the bend plane's normal t x s of a bent leg, turned toward the
/// knee's hinge (the thigh's lateral axis, about which SMPL knees flex positively); for a leg
/// straighter than kStraightLegSin, a blend that reaches the hinge when straight. The normal of a
/// nearly straight leg points wherever the knee's small off-hinge bend or a hyperextension puts it,
/// so using it there bent the knee sideways or backward, and the other way a frame later (knee and
/// ankle flips of the planted legs, issue 27).
Vec3 knee_bend_axis(const Vec3& t, const Vec3& s, const Vec3& hinge) {
  Vec3 h = hinge - hinge.dot(t) * t;
  h = h.norm() > 1e-9 ? Vec3(h.normalized()) : any_perpendicular(t);
  const Vec3 b = t.cross(s);
  const double m = b.norm();
  if (m < 1e-12) return h;
  const Vec3 b_hat = b.dot(h) < 0.0 ? Vec3(-b / m) : Vec3(b / m);
  const double x = std::clamp(m / kStraightLegSin, 0.0, 1.0);
  const double alpha = x * x * (3.0 - 2.0 * x);  // smoothstep: the axis moves continuously
  return (alpha * b_hat + (1.0 - alpha) * h).normalized();
}

/// +1: the knee ends flexed forward; -1: backward. A leg bent backward keeps that side when it gets
/// longer or stays (the least change), and also when shortened if it is bent back by more than
/// kHyperextension_rad; a nearly straight leg that must get shorter flexes forward, as knees do.
double knee_branch(double phi_now, bool shorten) {
  if (phi_now >= 0.0) return 1.0;
  return shorten && phi_now > -kHyperextension_rad ? 1.0 : -1.0;
}
}  // namespace

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
  // Knee: the angle phi between thigh and shank directions in the bend plane sets the hip-ankle
  // distance, d^2 = l1^2 + l2^2 + 2 l1 l2 r cos(phi), r = the shank's share in that plane.
  const Vec3 t = (knee - hip) / l1, s = (ankle - knee) / l2;
  const Vec3 n = knee_bend_axis(t, s, thigh * Vec3::UnitX());
  const double r = (s - s.dot(n) * n).norm();
  const double phi_now = std::atan2(t.cross(s).dot(n), t.dot(s));
  const double cos_goal = (d_goal * d_goal - l1 * l1 - l2 * l2) / (2.0 * l1 * l2);
  const double phi_goal = knee_branch(phi_now, cos_goal < t.dot(s) - 1e-12) *
                          std::acos(std::clamp(r > 1e-12 ? cos_goal / r : 1.0, -1.0, 1.0));
  const Quat flex(Eigen::AngleAxisd(phi_goal - phi_now, n));
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
  // The gap: out of the leg's length, plus what a knee bent off its hinge plane cannot straighten
  // (r < 1: the shank's off-plane share stays; sub-millimetre on nearly straight legs).
  const double shortfall = std::abs((ankle_flexed - hip).norm() - d_goal);
  return std::abs(d_goal_raw - d_goal) + (shortfall > 1e-9 ? shortfall : 0.0);
}

}  // namespace crowdlab
