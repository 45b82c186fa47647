#include "framework/core/penetration_depth.hpp"

#include <algorithm>

#include "framework/core/capsule_box.hpp"

namespace crowdlab {

double max_penetration_depth(const WorldCapsules& a, const WorldCapsules& b) {
  const Aabb ba = capsules_box(a), bb = capsules_box(b);
  if (!ba.overlaps(bb)) return 0.0;
  double depth = 0.0;
  for (const Capsule& ca : a) {
    // The capsule's bounding sphere (centre at the segment midpoint) must reach the other body's box.
    const double r = 0.5 * ca.length_m() + ca.radius_m;
    if (bb.squared_distance(0.5 * (ca.a + ca.b)) > r * r) continue;
    for (const Capsule& cb : b) depth = std::max(depth, capsule_contact(ca, cb).depth_m);
  }
  return depth;
}

}  // namespace crowdlab
