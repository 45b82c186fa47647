#pragma once
// Signed distance from a point to a capsule's surface (core/capsule.hpp): |p - closest point of the
// axis| - r, negative inside. Used by the proxy-coverage measure and the proxy fitting of issue 27.
#include "framework/core/capsule.hpp"

namespace crowdlab {

/// Signed distance (m) from p to capsule c's surface (< 0 inside).
double point_capsule_distance(const Vec3& p, const Capsule& c);

}  // namespace crowdlab
