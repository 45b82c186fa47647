#pragma once
// Which bones a joint's rotation answers for (issue 27): the contact scope shared by the free-limb
// measure (framework/metrics/free_limb_deviation.hpp) and the correction's free-joint release
// (framework/correction/stage_free_joints.cpp), so that what the solver leaves alone is exactly what
// the measure calls free.
//
//   subtree_mask(j)   the bones joint j's local rotation moves: j and its descendants (kJointParent)
//   contact_scope(j)  subtree_mask(j), except for the root and the legs (hips, knees, ankles, feet),
//                     whose scope is the whole body: a push anywhere moves the pelvis, and the foot
//                     holds bend the legs to keep planted feet where they are, so a leg of a pushed body
//                     is part of its response, not a free limb.
// Masks are bit sets over the 24 bones (bit b = bone b = joint b).
#include <array>
#include <cstdint>

#include "framework/core/skeleton.hpp"

namespace crowdlab {

using BoneMask = std::uint32_t;  ///< bit b set = bone (joint) b
inline constexpr BoneMask kAllBones = (BoneMask{1} << kJointCount) - 1;

constexpr BoneMask subtree_mask(int joint) {
  BoneMask m = 0;
  for (int b = 0; b < kJointCount; ++b)
    for (int a = b; a >= 0; a = kJointParent[static_cast<size_t>(a)])
      if (a == joint) {
        m |= BoneMask{1} << b;
        break;
      }
  return m;
}

constexpr BoneMask contact_scope(int joint) {
  switch (joint) {
    case kPelvis:
    case kLeftHip:
    case kRightHip:
    case kLeftKnee:
    case kRightKnee:
    case kLeftAnkle:
    case kRightAnkle:
    case kLeftFoot:
    case kRightFoot:
      return kAllBones;
    default:
      return subtree_mask(joint);
  }
}

/// contact_scope of every joint, computed once at compile time: the correction looks masks up per
/// character and step, and computing one walks the tree (24 bones x their depth).
inline constexpr std::array<BoneMask, kJointCount> kContactScopes = [] {
  std::array<BoneMask, kJointCount> scopes{};
  for (int j = 0; j < kJointCount; ++j) scopes[static_cast<size_t>(j)] = contact_scope(j);
  return scopes;
}();

}  // namespace crowdlab
