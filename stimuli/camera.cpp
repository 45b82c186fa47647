#include "stimuli/camera.hpp"

#include <cmath>
#include <numbers>

namespace crowdlab::stimuli {

Mat4 Camera::view() const {
  const Vec3 f = (target - eye).normalized();
  const Vec3 up = std::abs(f.y()) > 0.999 ? Vec3::UnitZ() : Vec3::UnitY();
  const Vec3 s = f.cross(up).normalized();
  const Vec3 u = s.cross(f);
  Mat4 m = Mat4::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Vec3 Camera::up() const {
  return view().block<1, 3>(1, 0).transpose();
}

Mat4 Camera::projection() const {
  const double t = 1.0 / std::tan(0.5 * fov_y_deg * std::numbers::pi / 180.0);
  const double aspect = static_cast<double>(width) / height;
  Mat4 p = Mat4::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (far_m + near_m) / (near_m - far_m);
  p(2, 3) = 2.0 * far_m * near_m / (near_m - far_m);
  p(3, 2) = -1.0;
  return p;
}

std::optional<Eigen::Vector2d> Camera::project(const Vec3& world) const {
  const Eigen::Vector4d clip = projection() * view() * world.homogeneous();
  if (clip.w() <= 1e-9) return std::nullopt;
  const double x = clip.x() / clip.w(), y = clip.y() / clip.w();
  return Eigen::Vector2d((x + 1.0) * 0.5 * width, (1.0 - y) * 0.5 * height);
}

}  // namespace crowdlab::stimuli
