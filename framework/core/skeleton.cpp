#include "framework/core/skeleton.hpp"

#include <stdexcept>

namespace crowdlab {
namespace {
constexpr std::array<std::string_view, kJointCount> kNames = {
    "pelvis",     "left_hip",    "right_hip",    "spine1",      "left_knee",     "right_knee",
    "spine2",     "left_ankle",  "right_ankle",  "spine3",      "left_foot",     "right_foot",
    "neck",       "left_collar", "right_collar", "head",        "left_shoulder", "right_shoulder",
    "left_elbow", "right_elbow", "left_wrist",   "right_wrist", "left_hand",     "right_hand"};
}  // namespace

std::string_view joint_name(int joint) {
  if (joint < 0 || joint >= kJointCount) throw std::out_of_range("joint index out of range");
  return kNames[static_cast<size_t>(joint)];
}

std::optional<int> joint_from_name(std::string_view name) {
  for (int j = 0; j < kJointCount; ++j)
    if (kNames[static_cast<size_t>(j)] == name) return j;
  return std::nullopt;
}

int mirror_joint(int joint) {
  const std::string_view name = joint_name(joint);
  if (name.starts_with("left_")) return *joint_from_name("right_" + std::string(name.substr(5)));
  if (name.starts_with("right_")) return *joint_from_name("left_" + std::string(name.substr(6)));
  return joint;
}

bool is_stiff_joint(int joint) {
  return joint == kPelvis || joint == kLeftAnkle || joint == kRightAnkle || joint == kLeftFoot ||
         joint == kRightFoot;
}

}  // namespace crowdlab
