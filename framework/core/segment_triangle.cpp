// Where a parametric line meets a box or a triangle (segment_triangle.hpp).
#include "framework/core/segment_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace crowdlab {

bool segment_meets_box(const Vec3& p, const Vec3& d, const Vec3& lo, const Vec3& hi, double t0, double t1) {
  for (int k = 0; k < 3; ++k) {
    if (std::abs(d[k]) < 1e-300) {
      if (p[k] < lo[k] || p[k] > hi[k]) return false;
      continue;
    }
    double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

double segment_triangle_t(const Vec3& p, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 h = d.cross(e2);
  const double det = e1.dot(h);
  if (std::abs(det) < 1e-14) return -1.0;
  const Vec3 s = p - a;
  const double u = s.dot(h) / det;
  if (u < 0 || u > 1) return -1.0;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return -1.0;
  return e2.dot(q) / det;
}

}  // namespace crowdlab
