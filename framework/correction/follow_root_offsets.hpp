#pragma once
// The input a walking crowd is corrected toward, moved where the correction put its bodies (ours; seed
// 000 §3.3 holds the root to its input by a spring and §5 names foot sliding as a limit).
//
// In a dense walking flow the correction pushes whole bodies 10-20 cm off their input paths (the corridor
// at 6.66 /m^2), while the PD targets of the legs stay the input's: a planted foot is held where it landed
// and the leg stretches under the displaced pelvis, and at lift-off the leg turns back toward the input's
// local rotations within a few frames (most of the corridor's leg flips, session 27: of 323 flip
// joint-frames in 5 s, 241 in swing and 66 within 3 frames of lift-off; none mid-stance).
// follow_root_offsets re-plans the input after a first correction, per character:
//   o(t)       `share` of the first correction's horizontal root offset from the input, smoothed by a
//              Gaussian of `smoothing_s` (truncated at 3 sigma, weights renormalised at the clip's ends);
//   root       input root + o(t);
//   feet       each planted stretch of the input's foot (ankle or ball planted: the corrector's test on
//              foot_plant_speed_mps and foot_plant_height_m, input_foot_lifts.hpp) moves by o at the
//              stretch's middle frame, as one rigid footprint, so the new input does not skate; between two
//              stretches the offset eases from one footprint's to the next (raised cosine), before the first
//              and after the last it is theirs; legs are re-posed onto these feet by the least-change leg IK
//              (core/leg_ik.hpp reach_ankle), the foot's world rotation kept.
// Everything else (arms, trunk, head, the gait's timing) is the input's, and a character the first
// correction did not move (o = 0 on every frame) is returned exactly as it was.
//   inputs:  the input crowd and its first correction (same characters and frames), smoothing_s (s),
//            share (0..1), the plant test's foot_plant_speed_mps and foot_plant_height_m (m/s, m)
//   outputs: the re-planned input (shapes, meshes, environment and metadata of `input`)
#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab {

struct FollowRootDef {
  double smoothing_s = 0.3;  ///< Gaussian sigma of the root offset (s)
  /// The share of the offset followed. Half: the re-planned input meets the first correction halfway.
  /// Measured on the corridor at 6.66 /m^2 over 20 s (three runs each, docs/correction.md, session 27):
  /// the whole offset let the second correction push the crowd further still (root offsets p99 13 ->
  /// 17 cm) and its planted feet slid more (stance drift p99 7.2 -> 9.1-11.0 mm, over issue 18's 10 mm);
  /// half kept the drift (6.9 mm) and removed about as many flips as the whole (2,379-2,615 ->
  /// 1,736-2,285), with less float.
  double share = 0.5;
};

CrowdAnimation follow_root_offsets(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                   const FollowRootDef& def, const CorrectorParams& plant_test);

}  // namespace crowdlab
