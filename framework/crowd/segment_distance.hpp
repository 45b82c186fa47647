#pragma once
// Closest point on a 2D segment [a, b] to q (clamped projection). Used by every model's wall terms.
#include <algorithm>

#include "framework/core/math_types.hpp"

namespace crowdlab {

inline Vec2 closest_point_on_segment(const Vec2& a, const Vec2& b, const Vec2& q) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((q - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return a + t * ab;
}

}  // namespace crowdlab
