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
#include <array>
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

/// The frames of a walking or dancing gait with its foot contacts (walk_animation.hpp,
/// dance_animation.hpp, walk_from_clips.hpp).
struct GaitFrames {
  GaitFrames() = default;
  /// n frames and contact flags, all default.
  explicit GaitFrames(size_t n) : frames(n) { contact[0].resize(n), contact[1].resize(n); }
  std::vector<Pose> frames;                          ///< one per trajectory frame
  std::array<std::vector<std::uint8_t>, 2> contact;  ///< [left, right] foot planted on frame f
  double max_ik_error_m = 0.0;                       ///< largest unreachable-ankle residual (m)
};

/// Finishes output frame f of a gait from (padded) frame k: solves both legs of `pose` onto the feet,
/// records the contacts and the IK residual in `out` (sized already) and stores the normalised pose.
void store_gait_frame(const BodyShape& shape, Pose pose, const std::array<std::vector<FootState>, 2>& feet,
                      size_t k, size_t f, GaitFrames& out);

}  // namespace crowdlab::anim
