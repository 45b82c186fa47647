#pragma once
// Loop-closure blend that keeps planted feet planted (issue 28; used by correct_crowd.cpp's close_loop).
//
// The last `window` frames of a clip blend into other poses of the same frames (the loop pre-roll's
// output, which the clip must end on to loop): weight w(k) = raised cosine rising from 0 to 1 over the
// window, root lerped and rotations slerped (core/blend_poses.hpp). A plain blend moves every foot by
// w(k) x its distance between the two animations, planted feet too: a foot standing at A in the clip
// and at B in the pre-roll slides toward B while it stands (session 10: `ours`' stance-foot drift p99
// 14.8 mm at 5.55/m² with the pre-roll on, accepted <= 10 mm). Here each leg has its own weight, which
// rises only on the frames where the INPUT lifts that foot (neither its ankle nor its ball planted, by the
// corrector's own test: the input joint moves slower than foot_plant_speed_mps and is below
// foot_plant_height_m) and stays constant while the foot stands. The ankle goes to the leg-weighted mix of
// its two positions, and the ankle bone's world rotation to the leg-weighted slerp of its two rotations,
// by the least-change two-bone IK (core/leg_ik.hpp, reach_ankle), on the body-weighted blend. A foot that
// both animations hold in place therefore stays in place, and a foot moves to where the pre-roll puts it
// while it swings, as a stepping foot does. A leg that does not swing inside the window keeps the clip's
// foot (its weight stays 0): the loop then closes everywhere but at that foot, which both animations
// hold on the same anchor when it stood since before the pre-roll began.
//
// Inputs: `input` is the uncorrected crowd (its feet decide planted or not), `clip` the corrected crowd
// (same characters and frames), targets[c] the poses for the LAST targets[c].size() frames of character
// c's clip; window <= targets[c].size() and < the clip's frame count. The clip's frames before the
// window are not changed.
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab {

/// 0 at k = 0 rising to 1 at k = len (raised cosine); 1 beyond and for len <= 0.
double raised_cosine(int k, int len);

void blend_keeping_planted_feet(const CrowdAnimation& input, const std::vector<std::vector<Pose>>& targets,
                                int window, const CorrectorParams& params, CrowdAnimation& clip);

/// Over the last `window` frames of `clip` (a correction run again inside the loop closure), every foot the
/// INPUT plants stays where the clip's foot stood on the frame before the input set it down, moving only as
/// the input's foot moves while it stands (its rigid motion since then, so a ball or heel the input keeps
/// still stays still); after such a stance the foot returns to the clip's over the frames it swings. Why:
/// the closure's second correction lagged a swinging foot by up to 23 mm and set it down 12 mm from where
/// it stood the frame before (tests/data/pipeline/loop_seam.yaml, stance-foot drift p99 12.0 mm, session 13).
/// A foot that stands to the clip's end stays there; the loop then closes everywhere but at that foot.
void keep_planted_feet_planted(const CrowdAnimation& input, int window, const CorrectorParams& params,
                               CrowdAnimation& clip);

}  // namespace crowdlab
