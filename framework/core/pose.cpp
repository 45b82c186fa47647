#include "framework/core/pose.hpp"

#include <cmath>

#include "framework/core/body_shape.hpp"
#include "framework/core/error.hpp"

namespace crowdlab {

Pose Pose::rest(const BodyShape& shape) {
  Pose p;
  p.root_position_m = shape.joint_offsets_m[kPelvis];
  return p;
}

double Pose::heading_rad() const {
  const Vec3 fwd = local_rotations[kPelvis] * Vec3::UnitZ();
  return std::atan2(fwd.x(), fwd.z());
}

namespace {
// Farthest a root may be from the origin: scenes span at most 1 km (spec areas); beyond, centimetre steps
// lose exactness in double precision, and at 1e300 m (a fuzzed file) they stop advancing altogether.
constexpr double kMaxRootDistance_m = 1e5;
}  // namespace

void validate_pose(const Pose& pose, const std::string& context) {
  if (!pose.root_position_m.allFinite())
    throw InputError(context + ": root position is not finite (NaN or Inf)");
  if (!(pose.root_position_m.cwiseAbs().maxCoeff() <= kMaxRootDistance_m))
    throw InputError(context + ": root position is more than 100 km (kMaxRootDistance_m) from the origin");
  for (int j = 0; j < kJointCount; ++j) {
    const Quat& q = pose.local_rotations[static_cast<size_t>(j)];
    const std::string joint = std::string(joint_name(j));
    if (!q.coeffs().allFinite())
      throw InputError(context + ": joint '" + joint + "' rotation is not finite (NaN or Inf)");
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw InputError(context + ": joint '" + joint + "' rotation is not a unit quaternion (norm " +
                       std::to_string(q.norm()) + ")");
  }
}

}  // namespace crowdlab
