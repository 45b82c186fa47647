#include "framework/core/point_capsule_distance.hpp"

#include <algorithm>

namespace crowdlab {

double point_capsule_distance(const Vec3& p, const Capsule& c) {
  const Vec3 d = c.b - c.a;
  const double len_sq = d.squaredNorm();
  const double s = len_sq > 0 ? std::clamp((p - c.a).dot(d) / len_sq, 0.0, 1.0) : 0.0;
  return (p - (c.a + s * d)).norm() - c.radius_m;
}

}  // namespace crowdlab
