#include "framework/core/capsule_box_distance.hpp"

#include <cmath>

namespace crowdlab {

double sdf_box(const Box& box, const Vec3& p) {
  const Vec3 local = box.rotation.conjugate() * (p - box.center_m);
  const Vec3 q = local.cwiseAbs() - box.half_extents_m;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

CapsuleBoxDistance capsule_box_distance(const Capsule& capsule, const Box& box) {
  const Vec3 d = capsule.b - capsule.a;
  auto f = [&](double t) { return sdf_box(box, capsule.a + t * d); };
  // Golden-section search on [0, 1] for the minimum of the convex f.
  constexpr double kInvPhi = 0.6180339887498949;
  double lo = 0.0, hi = 1.0;
  double x1 = hi - kInvPhi * (hi - lo), x2 = lo + kInvPhi * (hi - lo);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < 48; ++i) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - kInvPhi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + kInvPhi * (hi - lo);
      f2 = f(x2);
    }
  }
  // The ends are candidates too (a minimum at t = 0 or 1 is approached but never evaluated).
  double best_t = 0.5 * (lo + hi), best = f(best_t);
  for (const double t : {0.0, 1.0}) {
    const double v = f(t);
    if (v < best) best = v, best_t = t;
  }
  return {best - capsule.radius_m, capsule.a + best_t * d};
}

Aabb box_bounds(const Box& box) {
  const Mat3 r = box.rotation.toRotationMatrix();
  const Vec3 extent = r.cwiseAbs() * box.half_extents_m;
  return {box.center_m - extent, box.center_m + extent};
}

}  // namespace crowdlab
