#pragma once
// Walking from motion-capture clips (animation.motion: clips with walk_clips), following any 2D
// trajectory with planted feet, blended over speeds: the data-driven counterpart of walk_animation.hpp.
//
// 1. Gait cycle per clip (extract_walk_cycle): the clip, retargeted onto the character's body
//    (retarget.hpp), is cut to ONE gait cycle, left-foot contact to the next left-foot contact, the one
//    nearest the middle of the clip with a duration of 0.6-2.0 s (normal walking: ~1.0-1.2 s, Murray
//    1964). A foot is in contact while its ball (SMPL "foot" joint) moves slower than 0.35 m/s (a
//    swing foot moves at ~2x the walking speed) within 5 cm of its stance level, the 20th percentile
//    of the ball's heights over the frames where it is that slow (robust to the dip when the foot rolls
//    over the toes at toe-off, and to odd frames at a clip's ends).
//    The cycle is expressed in its travel frame: the root's ground position relative to the straight
//    line from the cycle's start to its end (lateral sway and surge remain), and the pelvis heading
//    relative to that line's direction. The small mismatch between the cycle's last frame and its
//    first is spread linearly over the cycle (rotations by slerp, root offsets by lerp), so the cycle
//    loops seamlessly. Its speed is the travel distance over the duration (measured, not assumed).
// 2. Blend tree over speeds: cycles sorted by speed; at ground speed v the two cycles that bracket v
//    are blended linearly in v (pose slerp / lerp at the same normalised phase; clamped to the slowest
//    / fastest cycle outside their range). The phase advances by v / D(v) cycles per second, D the
//    blended cycle distance, so the feet cover exactly the ground the trajectory covers.
//    Standing (smoothed speed < 0.05 m/s): the character steps on at 80 % of the slowest cycle's
//    cadence to the next touch-down of either foot (where double support begins), then the phase holds
//    with both feet planted.
// 3. Trajectory following: root ground position = trajectory position + the cycle's offsets turned by
//    the trajectory's smoothed heading (smoothed_track.hpp); pelvis = heading * the cycle's pelvis.
// 4. Feet planted: contacts come from the blended cycle (weighted vote); each stance's ball is planted
//    where the blended clip puts it at the stance's middle frame (foot_track.hpp), swings ease between
//    plants, the pelvis is lowered only where a leg cannot reach (pelvis_height_limit.hpp), and the legs
//    are solved by analytic IK (leg_ik.hpp). Foot skate is therefore zero by construction (measured in
//    the tests); the upper body plays the clips unchanged.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "framework/animation/retarget.hpp"
#include "framework/animation/walk_animation.hpp"

namespace crowdlab {

struct WalkCycle {
  std::string source;        ///< the clip file (for messages)
  std::vector<Pose> frames;  ///< travel frame: root (lateral, height, surge), pelvis relative heading
  std::array<std::vector<std::uint8_t>, 2> contact;  ///< [left, right] per frame
  double fps = 30.0;
  double speed_mps = 0.0;   ///< travel distance / duration
  double distance_m = 0.0;  ///< travel distance per cycle
};

/// Throws InputError naming clip.source (the retargeted clip's file) when no complete gait cycle is found.
WalkCycle extract_walk_cycle(const RetargetedClip& clip, const BodyShape& shape, const std::string& source);

/// cycles: at least one (any order). phase0 in [0, 1): the starting phase. reaction as in
/// animate_walking (shoulder reactions rotate the upper body on top).
/// Throws InputError for an empty or non-finite trajectory, fps <= 0 or no cycles.
WalkResult animate_walking_from_clips(const BodyShape& shape, const std::vector<WalkCycle>& cycles,
                                      const AgentTrajectory& trajectory, double fps, double phase0,
                                      const std::vector<double>& reaction = {});

}  // namespace crowdlab
