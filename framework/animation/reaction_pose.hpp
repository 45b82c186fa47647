#pragma once
// The upper-body posture of a shoulder reaction (seed 001 §3.1.1: 7 of 9 people "consistently
// presented their torso" when brushing past someone; seed 000 §4.3 describes the same as "a rotation
// of the torso and shoulders with the arm passing last").
//
// weight w in [-1, 1]: w > 0 presents the torso to the LEFT (the other person passes on the
// character's +X side), w < 0 to the right; |w| is the blend (0 = plain walk, 1 = full reaction).
// At |w| = 1 the trunk turns 35 deg about the vertical toward the passing side, distributed
// pelvis 5 / spine1 6 / spine2 9 / spine3 15 deg (most at the thorax, as in shoulder-led avoidance);
// the neck and head turn back 22 deg so the gaze stays roughly along the path; the collar on the
// passing side retracts 10 deg and that arm trails 12 deg behind the body while the arm swing of
// both arms is damped by 70 %. Amplitudes: a 30-40 deg shoulder-line rotation is what mocap of close
// passing shows (Hoyet et al. 2016 Fig. 1; Olivier et al., Gait & Posture 2013); the split along the
// spine follows the thoracic share of axial rotation.
#include "framework/core/pose.hpp"

namespace crowdlab::anim {

inline constexpr double kReactionTrunkYawDeg = 35.0;

/// Applies the reaction on top of `pose` (local rotations of pelvis, spine, neck, head, collars,
/// shoulders). Leg rotations are untouched: call before leg IK so the legs follow the new pelvis.
void apply_reaction_upper_body(Pose& pose, double weight);

/// Arm-swing damping factor for a reaction weight (1 = no damping).
double reaction_arm_swing_factor(double weight);

}  // namespace crowdlab::anim
