#include "framework/core/align_two_axes.hpp"

namespace crowdlab {

namespace {
// Orthonormal frame whose first column is a and whose second lies in the (a, b) plane.
Mat3 frame_from(const Vec3& a, const Vec3& b) {
  const Vec3 x = a.normalized();
  Vec3 y = b - b.dot(x) * x;
  if (y.norm() < 1e-12) y = Vec3::UnitY() - Vec3::UnitY().dot(x) * x;
  if (y.norm() < 1e-12) y = Vec3::UnitZ() - Vec3::UnitZ().dot(x) * x;
  y.normalize();
  Mat3 m;
  m.col(0) = x;
  m.col(1) = y;
  m.col(2) = x.cross(y);
  return m;
}
}  // namespace

Quat align_two_axes(const Vec3& a0, const Vec3& b0, const Vec3& a1, const Vec3& b1) {
  const Mat3 r = frame_from(a1, b1) * frame_from(a0, b0).transpose();
  return Quat(r).normalized();
}

}  // namespace crowdlab
