#include "framework/body/cover_capsules.hpp"

#include <algorithm>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/point_capsule_distance.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {
namespace {

/// Share of `vertices` within tolerance of the capsules.
double share_within(const std::vector<Vec3>& vertices, const WorldCapsules& caps, double tolerance_m) {
  if (vertices.empty()) return 1.0;
  long within = 0;
  for (const Vec3& v : vertices) {
    double d = 1e300;
    for (const Capsule& c : caps) d = std::min(d, point_capsule_distance(v, c));
    if (d <= tolerance_m) ++within;
  }
  return static_cast<double>(within) / static_cast<double>(vertices.size());
}

}  // namespace

CoverReport cover_mesh_with_capsules(BodyShape& shape, const SkinnedMesh& mesh, double tolerance_m) {
  CoverReport report;
  const Pose rest = Pose::rest(shape);
  const BoneTransforms bones = forward_kinematics(shape, rest);
  // The mesh's rest frame is the rest pose's (core/skinned_mesh.hpp): skinning it there is the identity up to
  // the root's placement, which this makes exact.
  const std::vector<Vec3> vertices = skin_vertices(mesh, bones);
  const WorldCapsules caps = world_capsules(shape, bones);
  report.within_before = share_within(vertices, caps, tolerance_m);
  std::array<double, kJointCount> needed{};
  for (size_t j = 0; j < kJointCount; ++j) needed[j] = caps[j].radius_m;
  for (const Vec3& v : vertices) {
    size_t best = 0;
    double best_d = 1e300;
    for (size_t j = 0; j < kJointCount; ++j) {
      const double d = point_capsule_distance(v, caps[j]);
      if (d < best_d) {
        best_d = d;
        best = j;
      }
    }
    // 1 nm more, so that the round-off of recomputing the distance cannot leave v a hair outside.
    if (best_d > tolerance_m)
      needed[best] = std::max(needed[best], best_d + caps[best].radius_m - tolerance_m + 1e-9);
  }
  WorldCapsules grown = caps;
  for (size_t j = 0; j < kJointCount; ++j) {
    report.growth_m[j] = needed[j] - shape.capsules[j].radius_m;
    shape.capsules[j].radius_m = needed[j];
    grown[j].radius_m = needed[j];
  }
  compute_rest_contact_pairs(shape);
  report.within_after = share_within(vertices, grown, tolerance_m);
  return report;
}

}  // namespace crowdlab
