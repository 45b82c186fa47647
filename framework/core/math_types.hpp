#pragma once
// Shared linear-algebra vocabulary. Units: metres, seconds, radians. World frame is Y-up, ground y = 0.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace crowdlab {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// The cross-product matrix [v]x, so that skew(v) * u == v.cross(u).
inline Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

/// A rigid transform: rotation then translation (x_world = rotation * x_local + translation).
struct RigidTransform {
  Quat rotation = Quat::Identity();
  Vec3 translation = Vec3::Zero();

  Vec3 apply(const Vec3& p) const { return rotation * p + translation; }
  RigidTransform operator*(const RigidTransform& rhs) const {
    return {rotation * rhs.rotation, rotation * rhs.translation + translation};
  }
};

}  // namespace crowdlab
