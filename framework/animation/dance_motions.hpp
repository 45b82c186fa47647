#pragma once
// The library of procedural dance / idle motions for stationary crowds (seed 000 §4.1 used 15
// looping Mixamo dance clips; these are 16 procedural stand-ins that need no external data).
//
// Each motion is a pure function of the beat count b (beats since the loop start, real-valued) and an
// amplitude a (~0.75-1.25), periodic in b with period `loop_beats`, so every motion loops seamlessly
// by construction (all terms are harmonics of 1 / loop_beats). It returns a DancePose: offsets and
// angles in the character frame (+X left, +Y up, +Z forward; radians, metres) that
// dance_animation.cpp turns into a skeleton pose with planted feet.
// Feet: a foot is on the ground exactly when its lift is 0; its horizontal offset only changes while
// it is lifted (so planted feet never slide).
#include <array>
#include <string_view>

#include "framework/core/math_types.hpp"

namespace crowdlab {

struct DanceArm {
  double raise = 0.15;  ///< angle of the upper arm from hanging down (0) to overhead (pi)
  double plane = 0.0;   ///< elevation plane: 0 = sideways (abduction), pi/2 = forward (flexion)
  double elbow = 0.3;   ///< elbow flexion (rad)
  double shrug = 0.0;   ///< collar elevation (rad)
};

struct DanceFoot {
  double dx = 0.0;    ///< lateral offset from the neutral stance, outward positive (m)
  double dz = 0.0;    ///< forward offset (m)
  double lift = 0.0;  ///< height above the ground (m); 0 = planted
  double heel = 0.0;  ///< heel rise about the ball (rad)
};

struct DancePose {
  Vec3 pelvis_offset = Vec3::Zero();  ///< x left, y up (negative = knees bend), z forward (m)
  double pelvis_yaw = 0, pelvis_roll = 0, pelvis_pitch = 0;
  double spine_yaw = 0, spine_roll = 0, spine_pitch = 0;  ///< summed over spine1..3
  double head_yaw = 0, head_pitch = 0, head_roll = 0;     ///< summed over neck + head
  std::array<DanceArm, 2> arm;                            ///< [left, right]
  std::array<DanceFoot, 2> foot;                          ///< [left, right]
};

struct DanceMotion {
  std::string_view name;
  double loop_beats;  ///< period of the motion in beats
  bool idle;          ///< an idle (non-dance) motion: tempo is halved
  DancePose (*evaluate)(double beat, double amplitude);
};

/// The 16 motions: bounce, sway, wave_overhead, fist_pump, jump, head_nod, clap, step_touch, twist,
/// shoulder_shimmy, hands_up_sway, point_up, knee_pop, idle_weight_shift, idle_hands_together,
/// clap_overhead.
const std::array<DanceMotion, 16>& dance_motions();

}  // namespace crowdlab
