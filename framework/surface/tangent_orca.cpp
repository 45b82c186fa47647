#include "framework/surface/tangent_orca.hpp"

#include <cmath>

namespace crowdlab {

void tangent_basis(const Vec3& up, Vec3& e1, Vec3& e2) {
  // Any axis not nearly parallel to `up` gives a well-conditioned cross product.
  const Vec3 ref = std::abs(up.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  e1 = up.cross(ref).normalized();
  e2 = up.cross(e1);
}

orca::Line orca_half_plane(const Vec2& p, const Vec2& v, const Vec2& velocity, double R, double tau,
                           double dt) {
  const double dist2 = p.squaredNorm(), R2 = R * R;
  Vec2 u, n;
  if (dist2 > R2) {
    const Vec2 w = v - p / tau;  // from the cut-off disc centre to the relative velocity
    const double w2 = w.squaredNorm(), wp = w.dot(p);
    if (wp < 0.0 && wp * wp > R2 * w2) {
      // Nearest boundary is the cut-off circle.
      const double wl = std::sqrt(w2);
      n = w / wl;
      u = (R / tau - wl) * n;
    } else {
      // Nearest boundary is a leg of the cone; which one from the sign of det(p, w).
      const double leg = std::sqrt(dist2 - R2);
      Vec2 dir;
      if (p.x() * w.y() - p.y() * w.x() > 0.0)
        dir = Vec2(p.x() * leg - p.y() * R, p.x() * R + p.y() * leg) / dist2;  // left leg
      else
        dir = -Vec2(p.x() * leg + p.y() * R, -p.x() * R + p.y() * leg) / dist2;  // right leg
      const double along = v.dot(dir);
      u = along * dir - v;
      n = Vec2(-dir.y(), dir.x());  // the leg's outer side is the left of its direction
    }
  } else {
    // Overlapping: leave the overlap within one step.
    const Vec2 w = v - p / dt;
    const double wl = w.norm();
    n = wl > 1e-12 ? Vec2(w / wl) : Vec2(-p.normalized());
    u = (R / dt - wl) * n;
  }
  orca::Line line;
  const Vec2 point = velocity + 0.5 * u;
  line.px = point.x();
  line.py = point.y();
  // The permitted side {(v' - point) . n >= 0} is the left of direction d = (n.y, -n.x), since
  // det(d, x) = n . x.
  line.dx = n.y();
  line.dy = -n.x();
  return line;
}

Vec2 solve_orca(const orca::Line* lines, std::size_t n, const Vec2& preferred, double max_speed,
                orca::Line* scratch) {
  double rx = 0, ry = 0;
  const std::size_t failed = orca::lp2(lines, n, max_speed, preferred.x(), preferred.y(), false, rx, ry);
  if (failed < n) orca::lp3(lines, n, 0, failed, max_speed, scratch, rx, ry);
  return Vec2(rx, ry);
}

}  // namespace crowdlab
