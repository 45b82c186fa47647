#include "framework/core/rotation_angle.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace crowdlab {

double rotation_angle_deg(const Quat& a, const Quat& b) {
  const double d = std::min(1.0, std::abs(a.normalized().dot(b.normalized())));
  return 2.0 * std::acos(d) * 180.0 / std::numbers::pi;
}

}  // namespace crowdlab
