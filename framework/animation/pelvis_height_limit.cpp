#include "framework/animation/pelvis_height_limit.hpp"

#include <algorithm>
#include <cmath>

namespace crowdlab::anim {

void limit_pelvis_height(const BodyShape& shape, std::vector<double>& root_height,
                         const std::vector<Quat>& pelvis_rotation, const std::vector<Vec3>& root_xz,
                         const std::array<const std::vector<FootState>*, 2>& feet, double reach_fraction,
                         int smoothing_radius) {
  const size_t n = root_height.size();
  std::vector<double> limit(root_height);
  for (size_t k = 0; k < n; ++k) {
    for (LegSide side : {LegSide::kLeft, LegSide::kRight}) {
      const double reach = reach_fraction * leg_length(shape, side);
      const Vec3 hip_rel =
          pelvis_rotation[k] * shape.joint_offsets_m[static_cast<size_t>(leg_joints(side).hip)];
      const Vec3 hip_ground(root_xz[k].x() + hip_rel.x(), 0.0, root_xz[k].z() + hip_rel.z());
      const Vec3& ankle = (*feet[side == LegSide::kLeft ? 0 : 1])[k].ankle;
      const double horiz = std::hypot(ankle.x() - hip_ground.x(), ankle.z() - hip_ground.z());
      const double vertical = std::sqrt(std::max(reach * reach - horiz * horiz, 0.0));
      limit[k] = std::min(limit[k], ankle.y() - hip_rel.y() + vertical);
    }
  }
  const auto r = static_cast<size_t>(std::max(smoothing_radius, 0));
  std::vector<double> running_min(n);
  for (size_t k = 0; k < n; ++k) {
    const size_t lo = k >= r ? k - r : 0, hi = std::min(n - 1, k + r);
    running_min[k] = *std::min_element(limit.begin() + static_cast<std::ptrdiff_t>(lo),
                                       limit.begin() + static_cast<std::ptrdiff_t>(hi) + 1);
  }
  for (size_t k = 0; k < n; ++k) {
    const size_t lo = k >= r ? k - r : 0, hi = std::min(n - 1, k + r);
    double sum = 0;
    for (size_t i = lo; i <= hi; ++i) sum += running_min[i];
    root_height[k] = sum / static_cast<double>(hi - lo + 1);
  }
}

}  // namespace crowdlab::anim
