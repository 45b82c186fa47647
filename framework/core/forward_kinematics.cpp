#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

BoneTransforms forward_kinematics(const BodyShape& shape, const Pose& pose) {
  BoneTransforms out;
  out[0] = {pose.local_rotations[0], pose.root_position_m};
  for (int j = 1; j < kJointCount; ++j) {
    const RigidTransform& parent = out[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])];
    out[static_cast<size_t>(j)] = parent * RigidTransform{pose.local_rotations[static_cast<size_t>(j)],
                                                          shape.joint_offsets_m[static_cast<size_t>(j)]};
  }
  return out;
}

std::array<Vec3, kJointCount> joint_positions(const BodyShape& shape, const Pose& pose) {
  const BoneTransforms bones = forward_kinematics(shape, pose);
  std::array<Vec3, kJointCount> p;
  for (size_t j = 0; j < bones.size(); ++j) p[j] = bones[j].translation;
  return p;
}

WorldCapsules world_capsules(const BodyShape& shape, const BoneTransforms& bones) {
  WorldCapsules out;
  for (size_t j = 0; j < out.size(); ++j) out[j] = shape.capsules[j].transformed(bones[j]);
  return out;
}

WorldCapsules world_capsules(const BodyShape& shape, const Pose& pose) {
  return world_capsules(shape, forward_kinematics(shape, pose));
}

Pose pose_from_bone_transforms(const BoneTransforms& bones) {
  Pose p;
  p.root_position_m = bones[0].translation;
  p.local_rotations[0] = bones[0].rotation.normalized();
  for (int j = 1; j < kJointCount; ++j) {
    const Quat& parent = bones[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])].rotation;
    p.local_rotations[static_cast<size_t>(j)] =
        (parent.conjugate() * bones[static_cast<size_t>(j)].rotation).normalized();
  }
  return p;
}

}  // namespace crowdlab
