// Exact capsule-box contact (see environment_box_contact.hpp).
#include "framework/correction/environment_box_contact.hpp"

#include "framework/core/capsule_box_distance.hpp"

namespace crowdlab {

bool environment_box_contact(const Capsule& cap, const Box& box, const Vec3& root, double min_penetration_m,
                             EnvironmentBoxContact& out) {
  const CapsuleBoxDistance d = capsule_box_distance(cap, box);
  if (!(-d.distance_m > min_penetration_m)) return false;
  const Vec3 local = box.rotation.conjugate() * (d.axis_point - box.center_m);
  const Vec3 nearest = local.cwiseMax(-box.half_extents_m).cwiseMin(box.half_extents_m);
  out.axis_point = d.axis_point;
  const double gap = (local - nearest).norm();
  if (gap > 1e-9) {
    out.normal = box.rotation * ((local - nearest) / gap);
    out.penetration_m = -d.distance_m;
    return true;
  }
  const Vec3 r = box.rotation.conjugate() * (root - box.center_m);
  Eigen::Index axis = 0;
  (r.cwiseAbs() - box.half_extents_m).maxCoeff(&axis);
  const double side = r[axis] >= 0.0 ? 1.0 : -1.0;
  out.normal = box.rotation * (side * Vec3::Unit(axis));
  out.penetration_m = cap.radius_m + box.half_extents_m[axis] - side * local[axis];
  return true;
}

}  // namespace crowdlab
