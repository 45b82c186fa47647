#pragma once
// Retargeting BVH motion onto crowdlab's 24-joint SMPL skeleton and a target body.
//
// 1. Name maps (joint_name_map.cpp): the source skeleton's naming convention is detected (Mixamo
//    "mixamorig:LeftUpLeg", CMU "LeftUpLeg"/"LowerBack", Bandai-Namco "UpperLeg_L", SMPL "left_hip" or
//    "L_Hip") and each SMPL joint gets at most one source joint. Pelvis, hips, knees and ankles are
//    required; other joints may be missing (they then keep the parent's orientation).
// 2. Rest-pose alignment: the source's zero pose (all channels 0) may be anything: a T-pose (Mixamo),
//    or limbs laid along local axes (Bandai-Namco). For each mapped joint j the rest-offset rotation
//    A_j maps the source's zero-pose bone direction (towards the next mapped joint down the chain) onto
//    the target's T-pose bone direction; for the pelvis and the upper spine (spine3) a second,
//    lateral direction between their direct children (left minus right hip / collar) fixes the twist
//    (align_two_axes). Other bones have one child: their twist moves no joint but turns a skinned head or
//    hand, so it is inherited from the parent's alignment (A_j = minimal arc after A_parent). The target
//    bone's world rotation is then W_j(t) = G_j(t) * A_j^-1, where G_j(t) is the source joint's world
//    rotation: every mapped bone points where the source bone points, whatever the rest poses.
// 3. Feet: each foot is turned about its lateral axis so that it is flat (at the target's rest
//    pitch) while it stands (its 20 % lowest frames), since ankle-over-toe geometry differs between
//    skeletons; the toes keep their world orientation.
// 4. Scaling: root translation is scaled by target leg length / source leg length (hip-knee-ankle),
//    and shifted vertically so that the lowest contact point (ankle or ball, above its rest height)
//    is at 0 in 10 % of the frames (feet on the ground whatever the source's units or ground level).
// The source must be Y-up (BVH convention) or Z-up (detected from the first frame, head above hips).
#include <array>
#include <string>
#include <vector>

#include "framework/animation/bvh.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {

enum class SkeletonConvention { kMixamo, kCmu, kBandaiNamco, kSmpl };
std::string_view to_string(SkeletonConvention c);

struct JointMap {
  SkeletonConvention convention = SkeletonConvention::kSmpl;
  std::array<int, kJointCount> source{};  ///< source joint index per SMPL joint, -1 when unmapped
};

/// Detects the convention and maps names. Throws InputError (naming the file) when the required
/// joints cannot be found.
JointMap map_joint_names(const BvhMotion& motion);

struct RetargetedClip {
  std::vector<Pose> frames;
  double fps = 30.0;
  JointMap map;
  double scale = 1.0;  ///< target / source length ratio applied to root motion
};

struct RetargetOptions {
  bool flatten_feet = true;  ///< step 3 above
};

RetargetedClip retarget_bvh(const BvhMotion& motion, const BodyShape& target,
                            const RetargetOptions& options = {});

/// Moves and turns a clip on the ground so that frame 0's root is above the origin and its heading
/// is 0 (facing +Z). Heights are unchanged.
void normalize_clip_start(std::vector<Pose>& frames);

}  // namespace crowdlab
