#pragma once
// Joint flips (issue 27): a corrected joint that suddenly turns away from its input, e.g. a wrist that
// turns by ~90 degrees within 2-3 frames while the input's hand moves smoothly.
//
// For character c, joint j and frame f let D(f) = R_hat(f)^-1 R(f) be the deviation of the corrected
// local rotation R from the input's R_hat. Joint-frame (c, j, f) is a FLIP when D changed by more than
// A degrees within the last W frames (FlipWindow, from the clip's frame rate):
//     max_{k = 1..W, f - k >= first}  angle(D(f - k)^-1 D(f)) > A
// (for a clip that plays as a loop, f - k is taken around the loop instead).
// Comparing deviations (not rotations) cancels the input's own motion, and the angle of a unit
// quaternion difference is sign-free (rotation_angle_deg), so q and -q are the same rotation.
// Issue 27's threshold is 20 degrees within 3 frames, written for 30 fps clips: 200 deg/s of deviation
// alone over 0.1 s. It is kept in time, not frames (session 26): W = the frames nearest 0.1 s (at least
// 1) and A = 200 deg/s x W / fps, so 30 and 60 fps give 20 degrees (3 and 6 frames) and 15 fps 26.7
// degrees within 2 frames. Counted in frames, the demo's 15 fps clips flagged 13 deg per frame, which is
// the corrector's return rate for a released joint (free_joint_return_radps, 3.4 rad/s), as a flip.
//   inputs:  the input and the corrected animation (same characters, frames and meta.fps), the first
//            frame counted
//   outputs: flip joint-frames (count, per joint, the first kListedFlips) and the largest deviation
//            change within the window (degrees)
// In core, not metrics: the correction stage's loop closure uses it too (correct_crowd.cpp, no closure
// that adds flips to a character), and correction comes before metrics in the stage order.
#include <array>
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Deviation change rate (deg/s) over about kFlipWindow_s that is a flip: 20 deg within 3 frames at 30 fps.
inline constexpr double kFlipRate_degps = 200.0;
inline constexpr double kFlipWindow_s = 0.1;

/// The flip window of a clip at `fps` frames per second.
struct FlipWindow {
  int frames = 3;           ///< W: frames compared back (the frames nearest kFlipWindow_s, at least 1)
  double angle_deg = 20.0;  ///< A: kFlipRate_degps over those frames
};
/// Throws InputError for fps that is not finite and positive.
FlipWindow flip_window(double fps);
/// How many flips JointFlips lists (the first ones, by character, joint and frame).
inline constexpr size_t kListedFlips = 10;

struct JointFlip {
  int character = 0, joint = 0, frame = 0;
  double change_deg = 0.0;  ///< the largest deviation change within the window
};

struct JointFlips {
  long count = 0;                ///< flip joint-frames
  double max_change_deg = 0.0;   ///< largest deviation change within the window, any joint-frame
  std::vector<JointFlip> first;  ///< the first kListedFlips, ordered by (character, joint, frame)
  std::array<long, kJointCount> per_joint{};  ///< flip joint-frames per joint (where they are)
};

/// Frames from first_frame on, the window from corrected.meta.fps; `looped`: the clip plays as a loop, so
/// the window of its first frames reaches back around the loop to its last (a jump at the seam is a flip
/// to the viewer). The animations must match in characters and frames (caller checks).
JointFlips measure_joint_flips(const CrowdAnimation& input, const CrowdAnimation& corrected,
                               int first_frame = 0, bool looped = false);

}  // namespace crowdlab
