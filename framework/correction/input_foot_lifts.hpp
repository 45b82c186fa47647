#pragma once
// Which frames an input animation lifts each foot on, by the corrector's plant test (stage_foot_holds.cpp):
// a foot joint (ankle or ball) that moved less than max_step_m since the frame before (foot_plant_speed_mps
// / fps) while below foot_plant_height_m is planted; a foot is lifted when neither of its joints is.
// Shared by the loop closure's blends (blend_keeping_planted_feet.cpp) and the footprints a walking crowd's
// second correction follows (follow_root_offsets.cpp).
//   inputs:  one character's animation, frames [first, first + window) (first >= 1), max_step_m (m per
//            frame), params.foot_plant_height_m (m)
//   outputs: lifted[side][k] for frame first + k, side 0 left, 1 right (kLegSides)
#include <array>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab {

std::array<std::vector<bool>, 2> lifted_frames(const CharacterAnimation& in, int first, int window,
                                               double max_step_m, const CorrectorParams& p);

}  // namespace crowdlab
