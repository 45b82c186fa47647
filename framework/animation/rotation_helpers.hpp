#pragma once
// Small rotation helpers shared by the procedural motions. Frames follow the skeleton convention:
// +Y up, +Z forward, +X the character's left. Angles in radians.
//   yaw(a)   rotates about +Y (a > 0 turns the face from +Z toward +X, i.e. to the character's left)
//   pitch(a) rotates about +X (a > 0 tips +Z downward: a forward bend for the trunk, toes-down for a foot)
//   roll(a)  rotates about +Z (a > 0 raises the left (+X) side)
#include <cmath>

#include "framework/core/align_two_axes.hpp"  // align_two_axes, used with these helpers
#include "framework/core/math_types.hpp"

namespace crowdlab::anim {

inline constexpr double kPi = 3.14159265358979323846;

inline Quat yaw(double a) {
  return Quat(Eigen::AngleAxisd(a, Vec3::UnitY()));
}
inline Quat pitch(double a) {
  return Quat(Eigen::AngleAxisd(a, Vec3::UnitX()));
}
inline Quat roll(double a) {
  return Quat(Eigen::AngleAxisd(a, Vec3::UnitZ()));
}

/// The rotation taking unit direction `from` onto unit direction `to` (shortest arc; any axis when
/// they are opposite).
inline Quat shortest_arc(const Vec3& from, const Vec3& to) {
  return Quat::FromTwoVectors(from.normalized(), to.normalized());
}

/// Wraps an angle to (-pi, pi].
inline double wrap_angle(double a) {
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a < 0) a += 2.0 * kPi;
  return a - kPi;
}

/// The fractional part of x, in [0, 1): the phase within a cycle counted in cycles.
inline double frac(double x) {
  return x - std::floor(x);
}

/// Hermite smoothstep on [0, 1] (zero slope at both ends); inputs outside are clamped.
inline double smoothstep01(double x) {
  x = x < 0 ? 0 : (x > 1 ? 1 : x);
  return x * x * (3.0 - 2.0 * x);
}

/// Raised-cosine ease on [0, 1]: 0.5 - 0.5 cos(pi x) (zero slope at both ends).
inline double cosine_ease(double x) {
  x = x < 0 ? 0 : (x > 1 ? 1 : x);
  return 0.5 - 0.5 * std::cos(kPi * x);
}

/// Heading (rotation about +Y) of a direction on the ground: atan2(x, z).
inline double heading_of(const Vec3& dir) {
  return std::atan2(dir.x(), dir.z());
}

}  // namespace crowdlab::anim
