#pragma once
// Procedural walking that follows any 2D trajectory (positions x, z and heading per frame).
//
// Pipeline (all offline over the whole trajectory, padded by 2 s of constant-velocity motion at both
// ends so the first and last steps are complete):
//  1. speed and turn rate from smoothed central differences;
//  2. gait phase: integrated stride frequency f(v) (gait_parameters.hpp, the walk ratio), scaled by an
//     activity a(v) = smoothstep over 0.05..0.25 m/s; a swing that has begun always completes at the
//     slow-walk tempo, so a stopping walker ends in double support; a standing agent that drifts more
//     than 0.15 m or turns more than 25 deg from where it stopped takes one full cycle of steps;
//  3. contacts: left stance while frac(phase) < 0.62, right stance half a cycle later;
//  4. foot plants: at each stance's middle the ankle is placed under the hip's ground track (shifted
//     back by 7 % of the stride, the asymmetry of heel strike vs toe off), half the hip width to the
//     side when walking (step width ~0.1 m), the full hip width when standing; the foot turns with
//     the heading at mid-stance, toed out 4 deg; heel rise about the ball over the last 45 % of stance;
//  5. pelvis: heading + pelvic rotation, pelvic list, lateral shift toward the stance foot, lean into
//     turns (atan(v w / g)), height lowered only as needed to reach both ankles (pelvis_height_limit);
//  6. legs by analytic two-bone IK (leg_ik.hpp), so planted feet do not skate; trunk counter-rotation,
//     contralateral arm swing with elbow flexion, head that looks 0.4 s ahead into turns;
//  7. standing agents idle: breathing and slow look-around.
// A shoulder reaction (shoulder_reaction.hpp) adds trunk rotation on top while the legs keep walking.
#include <array>
#include <cstdint>
#include <vector>

#include "framework/animation/foot_track.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab {

/// Per-character variation of the gait (drawn from the character's seed by walk_style_from_seed()).
struct WalkStyle {
  double phase0 = 0.0;           ///< initial gait phase in [0, 1)
  double arm_swing_scale = 1.0;  ///< multiplies the arm swing amplitude
  double sway_scale = 1.0;       ///< multiplies pelvic list / rotation / lateral sway
  double idle_phase = 0.0;       ///< phase of idle breathing / look-around, [0, 1)
};
WalkStyle walk_style_from_seed(std::uint64_t seed);

using WalkResult = anim::GaitFrames;

/// reaction: empty, or one signed weight per frame in [-1, 1] (> 0 presents the torso to the left,
/// toward +X of the character); see shoulder_reaction.hpp.
/// Throws InputError for an empty or non-finite trajectory or fps <= 0.
WalkResult animate_walking(const BodyShape& shape, const AgentTrajectory& trajectory, double fps,
                           const WalkStyle& style, const std::vector<double>& reaction = {});

}  // namespace crowdlab
