#pragma once
// Free-limb deviation (issue 27): how much a correction turns joints whose limbs touch nobody. A study
// that compares a corrected crowd with its input attributes every difference to resolved collisions;
// that holds only where the correction changes nothing but what collides.
//
// Joint j of character c is FREE on frame f when, on every frame of [f - w, f + w] (w = window_s x fps,
// clipped to the clip; for a clip that loops, taken around the loop, because a viewer sees its last frames
// just before its first), no bone of its scope is near anything (bone_proximity.hpp: within margin_m of
// another character's capsules or an environment box) in the input or in the corrected animation.
// The scope of a joint is contact_scope (core/joint_scope.hpp): the bones its local rotation moves
// (the joint and its descendants), and the whole body for the root and the legs (a leg of a pushed
// body is part of its response: the foot holds bend it to keep planted feet where they are).
// On every free joint-frame, the deviation is the angle between the input's and the corrected local
// rotations (degrees; core/rotation_angle.hpp). Reported: p99 (nearest rank) and max over all of them, how
// many there were, and where the max is.
#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

inline constexpr double kFreeLimbMargin_m = 0.10;  ///< issue 27: "farther than 10 cm"
inline constexpr double kFreeLimbWindow_s = 0.5;   ///< issue 27: "over a window of +-0.5 s"

struct FreeLimbDeviation {
  double p99_deg = 0.0;
  double max_deg = 0.0;
  long free_joint_frames = 0;  ///< joint-frames that were free (the samples)
  long joint_frames = 0;       ///< all joint-frames measured
  int worst_character = -1, worst_joint = -1, worst_frame = -1;  ///< where max_deg is (-1: none)
};

/// Frames from first_frame on; `looped`: the clip plays as a loop (its window wraps around the clip's end).
/// The animations must match in characters and frames (caller checks).
FreeLimbDeviation measure_free_limb_deviation(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                              int first_frame = 0, bool looped = false,
                                              double margin_m = kFreeLimbMargin_m,
                                              double window_s = kFreeLimbWindow_s);

}  // namespace crowdlab
