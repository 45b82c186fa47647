#include "framework/core/blend_poses.hpp"

namespace crowdlab {

Pose blend_poses(const Pose& a, const Pose& b, double w) {
  Pose out;
  out.root_position_m = (1.0 - w) * a.root_position_m + w * b.root_position_m;
  for (size_t j = 0; j < a.local_rotations.size(); ++j)
    out.local_rotations[j] = a.local_rotations[j].slerp(w, b.local_rotations[j]).normalized();
  return out;
}

}  // namespace crowdlab
