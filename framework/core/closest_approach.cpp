#include "framework/core/closest_approach.hpp"

#include <limits>

namespace crowdlab {

ClosestApproach closest_approach(const Vec2& p_i, const Vec2& v_i, const Vec2& p_j, const Vec2& v_j) {
  const Vec2 p = p_j - p_i, v = v_j - v_i;
  const double vv = v.squaredNorm();
  if (vv <= 1e-18) return {std::numeric_limits<double>::infinity(), p.norm()};
  const double ttca = -p.dot(v) / vv;
  return {ttca, (p + ttca * v).norm()};
}

}  // namespace crowdlab
