#pragma once
// Pose interpolation, shared by the animation stage (clip loops, clip blending) and the correction
// stage (its loop pre-roll, correct_crowd.hpp).
#include "framework/core/pose.hpp"

namespace crowdlab {

/// Root lerp, rotations slerp (shortest path); w = 0 gives a, w = 1 gives b.
Pose blend_poses(const Pose& a, const Pose& b, double w);

}  // namespace crowdlab
