#pragma once
// Time and distance to closest approach between two agents moving at constant velocity
// (seed 001, Eqs. 2 and 3):
//   ttca = -(p . v) / |v|^2   if |v| != 0, else +infinity
//   dtca = |p + ttca v|       (|p| when ttca is infinite)
// where p = p_j - p_i and v = v_j - v_i are j's position and velocity relative to i (2D, metres and
// metres/second). ttca is negative when the agents are moving apart (closest approach in the past).
#include "framework/core/math_types.hpp"

namespace crowdlab {

struct ClosestApproach {
  double ttca_s = 0.0;  ///< seconds; +inf when the relative velocity is zero
  double dtca_m = 0.0;  ///< metres
};

ClosestApproach closest_approach(const Vec2& p_i, const Vec2& v_i, const Vec2& p_j, const Vec2& v_j);

}  // namespace crowdlab
