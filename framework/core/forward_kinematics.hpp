#pragma once
// Forward kinematics on the 24-joint tree.
//   bone_world[j] = bone_world[parent(j)] * (offset_j, local_rotation_j)
//   bone_world[0] = (root_position, local_rotation_0)
// Inputs: a BodyShape (rest offsets, capsules) and a Pose. Outputs are in world coordinates (metres).
#include <array>

#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {

using BoneTransforms = std::array<RigidTransform, kJointCount>;  ///< bone frame -> world, (24)
using WorldCapsules = std::array<Capsule, kJointCount>;          ///< capsules in world frame, (24)

/// World transform of every bone frame.
BoneTransforms forward_kinematics(const BodyShape& shape, const Pose& pose);

/// Joint positions in world coordinates (the translations of forward_kinematics()).
std::array<Vec3, kJointCount> joint_positions(const BodyShape& shape, const Pose& pose);

/// Every bone's capsule in world coordinates.
WorldCapsules world_capsules(const BodyShape& shape, const Pose& pose);
WorldCapsules world_capsules(const BodyShape& shape, const BoneTransforms& bones);

/// Inverse of forward_kinematics for rotations: local rotations from world bone rotations.
/// Root position is taken from bones[0].translation.
Pose pose_from_bone_transforms(const BoneTransforms& bones);

}  // namespace crowdlab
