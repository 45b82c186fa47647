#include "framework/core/capsule.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace crowdlab {

double Capsule::volume_m3() const {
  const double r = radius_m;
  return std::numbers::pi * r * r * (length_m() + 4.0 / 3.0 * r);
}

Vec3 any_perpendicular(const Vec3& v) {
  // Cross with the world axis least aligned with v, which keeps the result well conditioned.
  const Vec3 n = v.normalized();
  const Vec3 axis =
      std::abs(n.x()) < 0.57 ? Vec3::UnitX() : (std::abs(n.y()) < 0.57 ? Vec3::UnitY() : Vec3::UnitZ());
  return n.cross(axis).normalized();
}

SegmentClosestPoints segment_closest_points(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  // Minimise |p0 + s d1 - q0 - t d2|^2 over the unit square (the standard clamped 2x2 solve,
  // e.g. Ericson, Real-Time Collision Detection §5.1.9), with explicit degenerate/parallel branches.
  constexpr double kEps = 1e-12;
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) {
    s = t = 0.0;
  } else if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;  // >= 0; ~0 when parallel
      if (denom > kEps * a * e) {
        s = std::clamp((b * f - c * e) / denom, 0.0, 1.0);
      } else {
        // Parallel: project q's extent onto p and take the middle of the overlap (or nearest end).
        const double s_q0 = std::clamp(-c / a, 0.0, 1.0);
        const double s_q1 = std::clamp((d1.dot(q1 - p0)) / a, 0.0, 1.0);
        s = 0.5 * (s_q0 + s_q1);
      }
      t = (b * s + f) / e;
      if (t < 0.0) {
        t = 0.0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1.0) {
        t = 1.0;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  SegmentClosestPoints out;
  out.s = s;
  out.t = t;
  out.point_on_p = p0 + s * d1;
  out.point_on_q = q0 + t * d2;
  out.distance_m = (out.point_on_p - out.point_on_q).norm();
  return out;
}

CapsuleContact capsule_contact(const Capsule& a, const Capsule& b) {
  const SegmentClosestPoints cp = segment_closest_points(a.a, a.b, b.a, b.b);
  CapsuleContact c;
  c.point_a = cp.point_on_p;
  c.point_b = cp.point_on_q;
  c.s = cp.s;
  c.t = cp.t;
  c.depth_m = a.radius_m + b.radius_m - cp.distance_m;
  if (cp.distance_m > 1e-9) {
    c.normal = (cp.point_on_p - cp.point_on_q) / cp.distance_m;
  } else {
    // Axes intersect: any direction perpendicular to both axes separates them locally.
    const Vec3 da = a.b - a.a, db = b.b - b.a;
    const Vec3 cross = da.cross(db);
    if (cross.squaredNorm() > 1e-18) {
      c.normal = cross.normalized();
    } else if (da.squaredNorm() > 1e-18) {
      c.normal = any_perpendicular(da);
    } else if (db.squaredNorm() > 1e-18) {
      c.normal = any_perpendicular(db);
    } else {
      c.normal = Vec3::UnitY();  // two coincident spheres: separate vertically
    }
  }
  return c;
}

}  // namespace crowdlab
