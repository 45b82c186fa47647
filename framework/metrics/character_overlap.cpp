#include "framework/metrics/character_overlap.hpp"

#include <algorithm>
#include <vector>

namespace crowdlab {
namespace {

/// Whether capsule c's bounding sphere (centre at the segment midpoint) reaches the box.
bool sphere_reaches(const Capsule& c, const Aabb& box) {
  const double r = 0.5 * c.length_m() + c.radius_m;
  return box.squared_distance(0.5 * (c.a + c.b)) <= r * r;
}

void append_reaching(const WorldCapsules& body, const Aabb& target, std::vector<Capsule>& out) {
  for (const Capsule& c : body)
    if (sphere_reaches(c, target)) out.push_back(c);
}

}  // namespace

OverlapVolume character_overlap(const WorldCapsules& a, const WorldCapsules& b,
                                const OverlapOptions& options) {
  const Aabb ba = capsules_box(a), bb = capsules_box(b);
  if (!ba.overlaps(bb)) return {};
  std::vector<Capsule> ca, cb;
  append_reaching(a, bb, ca);
  append_reaching(b, ba, cb);
  return overlap_volume(ca, cb, options);
}

OverlapVolume overlap_with_others(std::span<const WorldCapsules> bodies, std::span<const Aabb> bounds, int i,
                                  const OverlapOptions& options) {
  const auto self = static_cast<size_t>(i);
  std::vector<Capsule> others;
  Aabb touched;
  for (size_t j = 0; j < bodies.size(); ++j) {
    if (j == self || !bounds[self].overlaps(bounds[j])) continue;
    append_reaching(bodies[j], bounds[self], others);
    touched.extend(bounds[j]);
  }
  if (others.empty()) return {};
  std::vector<Capsule> mine;
  append_reaching(bodies[self], touched, mine);
  return overlap_volume(mine, others, options);
}

}  // namespace crowdlab
