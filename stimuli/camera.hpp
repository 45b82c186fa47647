#pragma once
// A pinhole camera (OpenGL conventions: right-handed view space looking down -Z, clip depth [-1, 1]).
#include <optional>

#include "framework/core/math_types.hpp"

namespace crowdlab::stimuli {

using Mat4 = Eigen::Matrix4d;

struct Camera {
  Vec3 eye = Vec3(0, 1.7, 10);  ///< world position (metres)
  Vec3 target = Vec3(0, 1, 0);  ///< world point at the image centre
  double fov_y_deg = 40.0;      ///< vertical field of view (degrees)
  double near_m = 0.1, far_m = 200.0;
  int width = 1920, height = 1080;  ///< image size (pixels)

  /// World -> view (gluLookAt with +Y up; an up vector is chosen automatically for straight-down views).
  Mat4 view() const;
  /// The image's up direction in the world (unit; the second row of view()).
  Vec3 up() const;
  /// View -> clip (gluPerspective).
  Mat4 projection() const;
  /// Pixel coordinates (x right, y DOWN from the top-left corner, pixel centres at +0.5) of a world
  /// point, or nullopt when it is behind the camera.
  std::optional<Eigen::Vector2d> project(const Vec3& world) const;
};

}  // namespace crowdlab::stimuli
