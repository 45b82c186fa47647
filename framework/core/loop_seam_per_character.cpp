#include "framework/core/loop_seam_per_character.hpp"

#include <algorithm>
#include <array>
#include <span>

#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {
namespace {

constexpr std::array<int, 10> kArms = {kLeftCollar, kRightCollar, kLeftShoulder, kRightShoulder, kLeftElbow,
                                       kRightElbow, kLeftWrist,   kRightWrist,   kLeftHand,      kRightHand};
constexpr std::array<int, 8> kLegs = {kLeftHip,   kRightHip,   kLeftKnee, kRightKnee,
                                      kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot};
constexpr std::array<int, 6> kTrunk = {kPelvis, kSpine1, kSpine2, kSpine3, kNeck, kHead};

using Joints = std::array<Vec3, kJointCount>;

/// Mean distance of `joints` between two frames' joint positions.
double step_m(const Joints& a, const Joints& b, std::span<const int> joints) {
  double sum = 0.0;
  for (int j : joints) sum += (a[static_cast<size_t>(j)] - b[static_cast<size_t>(j)]).norm();
  return sum / static_cast<double>(joints.size());
}

double median(std::vector<double> v) {
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

std::vector<CharacterSeam> loop_seam_per_character(const CrowdAnimation& crowd) {
  std::vector<CharacterSeam> out;
  if (crowd.frame_count() < 2) return out;
  std::array<int, kJointCount> all{};
  for (int j = 0; j < kJointCount; ++j) all[static_cast<size_t>(j)] = j;
  for (const CharacterAnimation& c : crowd.characters) {
    std::vector<Joints> p;
    p.reserve(c.frames.size());
    for (const Pose& pose : c.frames) p.push_back(joint_positions(c.shape, pose));
    std::vector<double> steps;
    for (size_t f = 0; f + 1 < p.size(); ++f) steps.push_back(step_m(p[f], p[f + 1], all));
    CharacterSeam s;
    s.seam_m = step_m(p.back(), p.front(), all);
    s.median_step_m = median(steps);
    s.arms_m = step_m(p.back(), p.front(), kArms);
    s.legs_m = step_m(p.back(), p.front(), kLegs);
    s.trunk_m = step_m(p.back(), p.front(), kTrunk);
    out.push_back(s);
  }
  return out;
}

}  // namespace crowdlab
