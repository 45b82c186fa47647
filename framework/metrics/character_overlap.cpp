#include "framework/metrics/character_overlap.hpp"

#include <algorithm>
#include <vector>

namespace crowdlab {
namespace {

/// Squared distance from point p to box [lo, hi].
double box_distance2(const BodyBounds& box, const Vec3& p) {
  const Vec3 q = p.cwiseMax(box.lo).cwiseMin(box.hi);
  return (p - q).squaredNorm();
}

/// Whether capsule c's bounding sphere (centre at the segment midpoint) reaches the box.
bool sphere_reaches(const Capsule& c, const BodyBounds& box) {
  const double r = 0.5 * c.length_m() + c.radius_m;
  return box_distance2(box, 0.5 * (c.a + c.b)) <= r * r;
}

void append_reaching(const WorldCapsules& body, const BodyBounds& target, std::vector<Capsule>& out) {
  for (const Capsule& c : body)
    if (sphere_reaches(c, target)) out.push_back(c);
}

}  // namespace

BodyBounds body_bounds(const WorldCapsules& capsules) {
  BodyBounds box{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
  for (const Capsule& c : capsules) {
    const Vec3 r = Vec3::Constant(c.radius_m);
    box.lo = box.lo.cwiseMin(c.a.cwiseMin(c.b) - r);
    box.hi = box.hi.cwiseMax(c.a.cwiseMax(c.b) + r);
  }
  return box;
}

OverlapVolume character_overlap(const WorldCapsules& a, const WorldCapsules& b,
                                const OverlapOptions& options) {
  const BodyBounds ba = body_bounds(a), bb = body_bounds(b);
  if (!ba.overlaps(bb)) return {};
  std::vector<Capsule> ca, cb;
  append_reaching(a, bb, ca);
  append_reaching(b, ba, cb);
  return overlap_volume(ca, cb, options);
}

OverlapVolume overlap_with_others(std::span<const WorldCapsules> bodies, std::span<const BodyBounds> bounds,
                                  int i, const OverlapOptions& options) {
  const auto self = static_cast<size_t>(i);
  std::vector<Capsule> others;
  BodyBounds touched{Vec3::Constant(HUGE_VAL), Vec3::Constant(-HUGE_VAL)};
  for (size_t j = 0; j < bodies.size(); ++j) {
    if (j == self || !bounds[self].overlaps(bounds[j])) continue;
    append_reaching(bodies[j], bounds[self], others);
    touched.lo = touched.lo.cwiseMin(bounds[j].lo);
    touched.hi = touched.hi.cwiseMax(bounds[j].hi);
  }
  if (others.empty()) return {};
  std::vector<Capsule> mine;
  append_reaching(bodies[self], touched, mine);
  return overlap_volume(mine, others, options);
}

double max_penetration_depth(const WorldCapsules& a, const WorldCapsules& b) {
  const BodyBounds ba = body_bounds(a), bb = body_bounds(b);
  if (!ba.overlaps(bb)) return 0.0;
  double depth = 0.0;
  for (const Capsule& ca : a) {
    if (!sphere_reaches(ca, bb)) continue;
    for (const Capsule& cb : b) depth = std::max(depth, capsule_contact(ca, cb).depth_m);
  }
  return depth;
}

}  // namespace crowdlab
