#pragma once
// Joint flips (issue 27): a corrected joint that suddenly turns away from its input, e.g. a wrist that
// turns by ~90 degrees within 2-3 frames while the input's hand moves smoothly.
//
// For character c, joint j and frame f let D(f) = R_hat(f)^-1 R(f) be the deviation of the corrected
// local rotation R from the input's R_hat. Joint-frame (c, j, f) is a FLIP when D changed by more than
// kFlipAngle_deg within the last kFlipFrames frames:
//     max_{k = 1..kFlipFrames, f - k >= first}  angle(D(f - k)^-1 D(f)) > kFlipAngle_deg.
// Comparing deviations (not rotations) cancels the input's own motion, and the angle of a unit
// quaternion difference is sign-free (rotation_angle_deg), so q and -q are the same rotation.
// 20 degrees within 3 frames is 200 deg/s of deviation alone at 30 fps (issue 27's threshold).
//   inputs:  the input and the corrected animation (same characters and frames), the first frame counted
//   outputs: flip joint-frames (count, per joint, the first kListedFlips) and the largest deviation
//            change within kFlipFrames (degrees)
// In core, not metrics: the correction stage's loop closure uses it too (correct_crowd.cpp, no closure
// that adds flips to a character), and correction comes before metrics in the stage order.
#include <array>
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

inline constexpr double kFlipAngle_deg = 20.0;
inline constexpr int kFlipFrames = 3;
/// How many flips JointFlips lists (the first ones, by character, joint and frame).
inline constexpr size_t kListedFlips = 10;

struct JointFlip {
  int character = 0, joint = 0, frame = 0;
  double change_deg = 0.0;  ///< the largest deviation change within the window
};

struct JointFlips {
  long count = 0;                ///< flip joint-frames
  double max_change_deg = 0.0;   ///< largest deviation change within kFlipFrames, any joint-frame
  std::vector<JointFlip> first;  ///< the first kListedFlips, ordered by (character, joint, frame)
  std::array<long, kJointCount> per_joint{};  ///< flip joint-frames per joint (where they are)
};

/// Frames from first_frame on. The animations must match in characters and frames (caller checks).
JointFlips measure_joint_flips(const CrowdAnimation& input, const CrowdAnimation& corrected,
                               int first_frame = 0);

}  // namespace crowdlab
