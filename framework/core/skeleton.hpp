#pragma once
// The 24-joint SMPL kinematic topology (Loper et al. 2015), the skeleton every crowdlab character uses.
//
// Joint j also names "bone j": the rigid body that joint j rotates, carrying one collision capsule
// (seed 000 §3.4: 24 bones per character, one capsule each). Index order is SMPL's, so parents
// always precede children and a single forward pass computes forward kinematics.
//
// Rest pose (all local rotations identity) is a T-pose in the character frame:
//   +Y up, +Z forward (the direction the character faces), +X the character's left.
#include <array>
#include <optional>
#include <string_view>

namespace crowdlab {

inline constexpr int kJointCount = 24;

enum Joint : int {
  kPelvis = 0,
  kLeftHip = 1,
  kRightHip = 2,
  kSpine1 = 3,
  kLeftKnee = 4,
  kRightKnee = 5,
  kSpine2 = 6,
  kLeftAnkle = 7,
  kRightAnkle = 8,
  kSpine3 = 9,
  kLeftFoot = 10,
  kRightFoot = 11,
  kNeck = 12,
  kLeftCollar = 13,
  kRightCollar = 14,
  kHead = 15,
  kLeftShoulder = 16,
  kRightShoulder = 17,
  kLeftElbow = 18,
  kRightElbow = 19,
  kLeftWrist = 20,
  kRightWrist = 21,
  kLeftHand = 22,
  kRightHand = 23,
};

/// Parent of each joint; -1 for the root (pelvis). parent[j] < j for every non-root joint.
inline constexpr std::array<int, kJointCount> kJointParent = {-1, 0, 0, 0,  1,  2,  3,  4,  5,  6,  7,  8,
                                                              9,  9, 9, 12, 13, 14, 16, 17, 18, 19, 20, 21};

/// SMPL joint names, snake_case ("pelvis", "left_hip", ..., "right_hand").
std::string_view joint_name(int joint);

/// Inverse of joint_name(); std::nullopt for an unknown name.
std::optional<int> joint_from_name(std::string_view name);

/// The mirror joint (left <-> right); centre-line joints map to themselves.
int mirror_joint(int joint);

/// True for the joints whose PD gains are raised against foot skate and trunk drift (seed 000 §3.3).
bool is_stiff_joint(int joint);

}  // namespace crowdlab
