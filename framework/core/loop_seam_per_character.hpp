#pragma once
// Which characters make a looping clip's seam (issue 28, session 14): per character, the world-space step
// from the clip's last frame back to its first beside its own typical frame step, and where on the body
// the seam step lies (arms, legs, trunk). The stimulus check's seam_step_ratio (stimuli/stimulus_check.hpp)
// is one on-screen number for the whole crowd; this splits the same last-to-first step by character and
// body part, without a camera, so a closure's residue can be traced to the characters that carry it.
//
// A step of a set of joints is the mean distance (m) its joints move between two frames (joint_positions,
// the 24 SMPL joints). Groups: arms = collars to hands (10 joints), legs = hips to feet (8), trunk =
// pelvis, spine, neck and head (6).
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct CharacterSeam {
  double seam_m = 0.0;         ///< step of all 24 joints from the last frame to the first
  double median_step_m = 0.0;  ///< median over consecutive frames of the same step
  double arms_m = 0.0, legs_m = 0.0, trunk_m = 0.0;  ///< the seam step of each group
  /// What the character adds to the crowd's seam beyond a normal step (may be negative).
  double excess_m() const { return seam_m - median_step_m; }
};

/// One entry per character, in crowd order; empty for a crowd of fewer than two frames.
std::vector<CharacterSeam> loop_seam_per_character(const CrowdAnimation& crowd);

}  // namespace crowdlab
