#pragma once
// The angle between two rotations given as unit quaternions, shared by the correction stage (its loop
// closure's joint-flip filter, joint_flips.hpp) and the metrics stage (joint deviation, free-limb
// deviation, flips).
//   input:  quaternions a, b (normalised here; any length > 0)
//   output: the angle of the rotation taking a to b, in degrees, 0..180:
//           2 acos(|a . b|), sign-free, so q and -q are the same rotation.
#include "framework/core/math_types.hpp"

namespace crowdlab {

/// Angle (degrees) between two unit quaternions as rotations.
double rotation_angle_deg(const Quat& a, const Quat& b);

}  // namespace crowdlab
