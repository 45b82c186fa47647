#pragma once
// Axis-aligned boxes around capsules (seed 000 §3.4, "Culling": the broad phase tests body AABBs and
// capsule AABBs before the exact capsule-capsule test).
//   capsule_box(c, grow_m)  the box of capsule c (world frame, m), grown by grow_m (m) on every side
//   capsules_box(caps)      the box of a set of capsules, e.g. one posed body (empty for no capsules)
#include <span>

#include "framework/core/aabb.hpp"
#include "framework/core/capsule.hpp"

namespace crowdlab {

inline Aabb capsule_box(const Capsule& c, double grow_m = 0.0) {
  const Vec3 r = Vec3::Constant(c.radius_m + grow_m);
  return {c.a.cwiseMin(c.b) - r, c.a.cwiseMax(c.b) + r};
}

inline Aabb capsules_box(std::span<const Capsule> caps) {
  Aabb box;
  for (const Capsule& c : caps) box.extend(capsule_box(c));
  return box;
}

}  // namespace crowdlab
