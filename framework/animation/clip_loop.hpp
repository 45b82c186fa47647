#pragma once
// Trimming a clip and making it loop seamlessly (seed 000 §4.1: "Each animation was manually cut and
// looped, to ensure seamless continuous animation"; here it is automatic).
//
// make_seamless_loop(frames, first, last, blend) keeps frames [first, last) and cross-fades the last
// `blend` frames toward the frames just before `first`, moved rigidly on the ground (translation in
// x/z + rotation about +Y) so that they continue from the loop's end: with D the ground transform
// taking frame `first`'s root onto frame `last`'s root,
//     out[k] = slerp(in[k], D * in[first - (last - k)], w_k),  w rising 0 -> 1 (raised cosine)
// over the last `blend` frames. Frame last-1 then blends into D*in[first-1], whose successor is
// D*in[first]: the loop plays on without a pop, and for locomotion each replay continues from where
// the previous one ended (the per-loop displacement is loop_displacement()).
// Requires blend <= first (frames before the loop to blend from) and first + blend < last.
#include <vector>

#include "framework/core/blend_poses.hpp"  // blend_poses(), used with the loops
#include "framework/core/pose.hpp"

namespace crowdlab {

struct LoopedClip {
  std::vector<Pose> frames;  ///< the loop, last frame flows into the first
  Vec3 displacement =
      Vec3::Zero();       ///< root ground translation per loop (x, 0, z), in frame 0's heading frame
  double turn_rad = 0.0;  ///< heading change per loop
};

/// Throws InputError for an invalid range.
LoopedClip make_seamless_loop(const std::vector<Pose>& frames, int first, int last, int blend);

/// Frame `k` (any k >= 0) of a loop played repeatedly, each replay continuing the ground motion.
Pose sample_loop(const LoopedClip& loop, long k);

}  // namespace crowdlab
