#pragma once
// Axis-aligned bounding box in world coordinates (metres). The default box is empty (lo > hi), so that
// extending it by the first point or box gives exactly that point or box. Comparisons are closed:
// boxes that share a face overlap, and a point on a face is contained. The broad phase of seed 000
// §3.4 ("Culling": body AABBs first) is written with these.
#include "framework/core/math_types.hpp"

namespace crowdlab {

struct Aabb {
  Vec3 lo = Vec3::Constant(1e300);   ///< minimum corner (m)
  Vec3 hi = Vec3::Constant(-1e300);  ///< maximum corner (m)

  void extend(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool overlaps(const Aabb& b) const {
    return (lo.array() <= b.hi.array()).all() && (b.lo.array() <= hi.array()).all();
  }
  bool contains(const Vec3& p) const {
    return (lo.array() <= p.array()).all() && (p.array() <= hi.array()).all();
  }
  /// The common part of two boxes (empty, lo > hi on some axis, when they do not overlap).
  Aabb intersection(const Aabb& b) const { return {lo.cwiseMax(b.lo), hi.cwiseMin(b.hi)}; }
  /// Squared distance (m^2) from p to the box; 0 inside it.
  double squared_distance(const Vec3& p) const { return (p - p.cwiseMax(lo).cwiseMin(hi)).squaredNorm(); }
};

}  // namespace crowdlab
