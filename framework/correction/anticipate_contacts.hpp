#pragma once
// Anticipated contacts (issue 27, session 13; ours, beside seed 000 §3, which corrects each frame
// causally). The corrector runs frame after frame: a forearm that the input swings at 15-25 deg per frame
// into a neighbour is stopped within a frame of the contact, so its deviation from the input
// D = R̂^-1 R grows by 15-25 deg per frame, a "flip" (core/joint_flips.hpp: more than 20 deg within 3
// frames). The offline correction knows the whole clip, so the deviation a contact needs can be started
// before the contact and undone after it, slowly enough not to flip, and the solve then only holds it.
//
// Inside the solve, not around it: a first run finds every contact and the deviation it needs; each
// chosen joint's deviation trajectory D(0..N-1) of that run is replaced by a ramp E (below), and the
// input with E on those joints becomes the TARGET of another run, which resolves again whatever the
// ramps bring into contact (Eq. 4's PD pulls toward the ramp; the release of free joints returns a
// joint to it). Applied to the output directly, the ramps left p99 depths of 75 mm (session 12): the
// ramped arm stands where no solve checked it.
//
//   toward(A, B, r)   the rotation from A toward B by at most r (slerp, shortest path); |Q| its angle
//   backward:  B(N-1) = D(N-1);  c = toward(B(f+1), D(f), r);  B(f) = D(f) if |D(f)| >= |c| else c
//   forward:   F(0) = B(0);      c = toward(F(f-1), B(f), r);  F(f) = B(f) if |B(f)| >= |c| else c
//   rate:      E(0) = F(0);      E(f) = toward(E(f-1), F(f), r)
//   target:    T_j(f) = R̂_j(f) E_j(f)
//
// The first two passes are the dilation of |D| by a cone of slope r (ramps up before, down after); the
// third bounds the change of E to r per frame also where the direction of D turns (the first two bound
// the angle, not the axis). With r = 4.6 deg per frame (anticipation_rate_radps = 2.4 at 30 fps) the
// target flips nowhere (13.8 deg within 3 frames) and the next run has 6 deg of the flip measure's
// 20 deg for what the solve adds; session 12 ramped at the release rate, 6.5 deg per frame (19.5 deg
// within 3 frames), and the second run's few degrees of contact response put the same elbows over 20
// (docs/correction.md, session 13). A clip closed into a loop is ramped around its seam (two laps).
#include <span>
#include <string>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab {

/// The joints of CorrectorParams::anticipated_joints: "none", "arms" (collars, shoulders, elbows),
/// "upper" (arms, spine, neck, head), "legs" (hips, knees), "all" (upper and legs). Never the pelvis
/// (the root carries the pushes) nor the wrists, hands, ankles and balls, whose deviation the step
/// already rate-limits against its target (stage_free_joints.cpp; ramped too they flipped 5-7x more,
/// session 12). Throws InputError naming the parameter for any other name.
std::vector<int> anticipated_joint_set(const std::string& name);

/// Throws InputError naming the parameter when an anticipation parameter is out of range.
void validate_anticipation_params(const CorrectorParams& params);

/// The ramp E of one deviation trajectory (above), r = max_turn_rad per frame; `looping`: frame N-1 is
/// followed by frame 0.
std::vector<Quat> ramp_deviations(const std::vector<Quat>& deviation, double max_turn_rad, bool looping);

/// `aims` (a copy of `input`) with the local rotations of `joints` set to the input's times the ramp of
/// `corrected`'s deviation from `input`. The crowds must match in characters and frames.
void ramp_contact_deviations(const CrowdAnimation& input, const CrowdAnimation& corrected,
                             std::span<const int> joints, double max_turn_rad, bool looping,
                             CrowdAnimation& aims);

}  // namespace crowdlab
