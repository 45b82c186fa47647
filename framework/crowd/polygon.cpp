#include "framework/crowd/polygon.hpp"

#include <cmath>
#include <limits>

#include "framework/core/error.hpp"
#include "framework/crowd/segment_distance.hpp"

namespace crowdlab {

Polygon2 rectangle_polygon(double width_m, double depth_m, const Vec2& c) {
  const double hw = 0.5 * width_m, hd = 0.5 * depth_m;
  return {c + Vec2(-hw, -hd), c + Vec2(hw, -hd), c + Vec2(hw, hd), c + Vec2(-hw, hd)};
}

double polygon_area(const Polygon2& poly) {
  double twice = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[(i + 1) % n];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * std::fabs(twice);
}

double polygon_perimeter(const Polygon2& poly) {
  double p = 0.0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) p += (poly[(i + 1) % n] - poly[i]).norm();
  return p;
}

bool polygon_contains(const Polygon2& poly, const Vec2& q) {
  bool inside = false;
  for (std::size_t i = 0, n = poly.size(), j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > q.y()) != (b.y() > q.y())) {
      const double x = a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (q.x() < x) inside = !inside;
    }
  }
  return inside;
}

Vec2 polygon_closest_boundary_point(const Polygon2& poly, const Vec2& q) {
  Vec2 best = poly.front();
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Vec2 c = closest_point_on_segment(poly[i], poly[(i + 1) % n], q);
    const double d2 = (c - q).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = c;
  }
  return best;
}

void validate_polygon(const Polygon2& poly, const std::string& what) {
  if (poly.size() < 3)
    throw InputError(what + ": an area needs at least 3 vertices, got " + std::to_string(poly.size()));
  for (const Vec2& v : poly)
    if (!std::isfinite(v.x()) || !std::isfinite(v.y())) throw InputError(what + ": vertex is not finite");
  const double area = polygon_area(poly);
  if (!(area > 1e-12)) throw InputError(what + ": the area is empty (" + std::to_string(area) + " m^2)");
}

}  // namespace crowdlab
