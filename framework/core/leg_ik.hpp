#pragma once
// Analytic two-bone leg IK on the SMPL skeleton (hip -> knee -> ankle), plus the foot orientation.
// Shared by the animation stage (placing walking and dancing feet) and the correction stage (holding
// planted feet where they landed after each solver step).
//
// Given a pose whose pelvis (root) is already set, solve_leg_ik() writes the local rotations of the
// hip, knee and ankle of one leg so that
//   - the ankle joint lands exactly on `ankle_target` (world, metres) when it is reachable,
//   - the knee bends in the plane containing the hip, the target and `knee_pole` (a world direction
//     the knee should point toward, e.g. the foot's forward), i.e. a pure hinge about the knee's
//     local lateral axis, and
//   - the ankle bone's world rotation equals `foot_rotation` (e.g. yaw(heading) * pitch(heel rise)).
// The ball ("foot") joint's local rotation (the toes) is left as it is.
// The reach is the law of cosines on the thigh and shank lengths (|offset(knee)|, |offset(ankle)|);
// targets closer than |l1 - l2| or farther than l1 + l2 are clamped onto the reachable shell, and the
// returned value is the remaining ankle error (metres, 0 when reachable).
#include "framework/core/body_shape.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {

enum class LegSide { kLeft, kRight };
/// Both sides, indexed as the per-leg arrays of the corrector (0 left, 1 right).
inline constexpr LegSide kLegSides[2] = {LegSide::kLeft, LegSide::kRight};

struct LegJoints {
  int hip, knee, ankle, foot;
};
LegJoints leg_joints(LegSide side);

/// Thigh + shank length of one leg (metres).
double leg_length(const BodyShape& shape, LegSide side);

/// The world position of the hip joint of `side` for the pose's root position and pelvis rotation.
Vec3 hip_position(const BodyShape& shape, const Pose& pose, LegSide side);

double solve_leg_ik(const BodyShape& shape, Pose& pose, LegSide side, const Vec3& ankle_target,
                    const Quat& foot_rotation, const Vec3& knee_pole);

/// Least-change two-bone IK: moves the ankle of a posed leg onto `ankle_target` (world, m) by the
/// smallest edit of the existing rotations, and sets the ankle bone's world rotation to
/// `foot_rotation`. The knee flexes or extends about its current bend axis (the thigh x shank normal,
/// turned toward the knee's hinge; for a leg bent less than 10 deg a continuous blend that reaches the
/// hinge, the thigh's lateral axis, when straight; a nearly straight knee that must shorten the leg
/// flexes forward) to give the hip-target distance, then the
/// whole leg swings about the hip by the shortest arc onto the target. Unlike solve_leg_ik the
/// thigh's and shank's twists and the knee's off-hinge components are kept, so a leg already on its
/// target is left exactly as it was. Targets out of reach are clamped onto the reachable shell as in
/// solve_leg_ik; returns the remaining ankle error (m, 0 when reachable). The hip must be a child of
/// the pelvis (SMPL).
double reach_ankle(const BodyShape& shape, Pose& pose, LegSide side, const Vec3& ankle_target,
                   const Quat& foot_rotation);

/// Ankle position for a foot whose ball (the SMPL "foot" joint) rests at `ball` with world rotation
/// `foot_rotation`: ball - foot_rotation * offset(foot).
Vec3 ankle_from_ball(const BodyShape& shape, LegSide side, const Vec3& ball, const Quat& foot_rotation);

}  // namespace crowdlab
