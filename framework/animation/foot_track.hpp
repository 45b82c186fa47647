#pragma once
// Foot tracks: where each foot is on every frame, from a contact schedule.
//
// During a contact interval (a maximal run of frames with contact = true) the ball of the foot (the
// SMPL "foot" joint) is planted at ONE world position and the foot keeps one heading: both are taken
// from the desired values at the interval's middle frame, so the foot cannot skate. Only the heel
// rises (pitch about the planted ball: a rotation that moves the ankle but not the ball).
// Between two contacts the ankle travels from its lift-off position to its touch-down position on a
// raised-cosine ease (zero velocity at both ends), lifted by peak_lift * sin(pi s); heading and pitch
// are interpolated. Frames before the first or after the last contact hold that contact's foot.
#include <cstdint>
#include <vector>

#include "framework/core/leg_ik.hpp"

namespace crowdlab::anim {

struct FootTarget {
  Vec3 ball = Vec3::Zero();  ///< desired ball (foot joint) position, world metres
  double yaw_rad = 0;        ///< foot heading (0 faces +Z)
  double pitch_rad = 0;      ///< heel rise, rotation about the foot's lateral axis (> 0: toes down)
  double lift_m = 0;         ///< when airborne: requested peak lift of this swing
};

struct FootState {
  Vec3 ankle = Vec3::Zero();         ///< world ankle position (IK target)
  Quat rotation = Quat::Identity();  ///< world rotation of the ankle bone
  Vec3 ball = Vec3::Zero();          ///< world ball position implied by ankle and rotation
  bool contact = false;
};

/// One FootState per frame. `contact` and `desired` have one entry per frame.
std::vector<FootState> plan_foot_track(const BodyShape& shape, LegSide side,
                                       const std::vector<std::uint8_t>& contact,
                                       const std::vector<FootTarget>& desired);

/// Solves both legs of `pose` (root already set) onto the feet's ankle targets and rotations by
/// solve_leg_ik(), each knee pointing between its foot's and the pelvis's forward directions.
/// Returns the larger unreachable-ankle residual (metres).
double solve_legs(const BodyShape& shape, Pose& pose, const FootState& left, const FootState& right);

/// World rotation of a foot with heading `yaw_rad` and heel rise `pitch_rad`.
Quat foot_rotation(double yaw_rad, double pitch_rad);

}  // namespace crowdlab::anim
