#pragma once
// Pose: one frame of one character: the root (pelvis) position in the world and 24 local joint
// rotations. local_rotations[0] is the root's world orientation; local_rotations[j] for j > 0 rotates
// bone j relative to its parent's bone frame. All quaternions are unit.
#include <array>
#include <string>

#include "framework/core/math_types.hpp"
#include "framework/core/skeleton.hpp"

namespace crowdlab {

struct BodyShape;

struct Pose {
  Vec3 root_position_m = Vec3::Zero();  ///< pelvis joint in world coordinates (metres)
  std::array<Quat, kJointCount> local_rotations;

  Pose() { local_rotations.fill(Quat::Identity()); }

  /// The rest (T-)pose standing on the ground at the world origin, facing +Z.
  static Pose rest(const BodyShape& shape);

  /// Heading (radians) of the root about +Y: 0 faces +Z, pi/2 faces +X (atan2(forward.x, forward.z)).
  double heading_rad() const;
};

/// Throws InputError("<context>: ...") if any value is NaN/Inf, a rotation is not unit within 1e-3, or the
/// root is over 100 km from the origin (pose.cpp). Use at every boundary where poses enter (files, API).
void validate_pose(const Pose& pose, const std::string& context);

}  // namespace crowdlab
