#include "framework/io/validate_environment.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab {

void validate_environment(const Environment& env, const std::string& context) {
  for (size_t k = 0; k < env.boxes.size(); ++k) {
    const Box& b = env.boxes[k];
    const std::string who = context + ": box " + std::to_string(k);
    if (!b.center_m.allFinite()) throw InputError(who + ": centre is not finite");
    if (!b.half_extents_m.allFinite() || (b.half_extents_m.array() <= 0.0).any())
      throw InputError(who + ": half extents must be positive and finite");
    if (!b.rotation.coeffs().allFinite() || std::abs(b.rotation.norm() - 1.0) > 1e-3)
      throw InputError(who + ": rotation is not a unit quaternion");
  }
  for (const TriangleMesh& m : env.meshes) {
    const std::string who = context + ": mesh '" + m.name + "'";
    if (m.triangles.empty() || m.vertices_m.size() < 3) throw InputError(who + ": has no triangles");
    for (const Vec3& v : m.vertices_m)
      if (!v.allFinite()) throw InputError(who + ": a vertex is not finite");
    for (const Eigen::Vector3i& t : m.triangles)
      if ((t.array() < 0).any() || (t.array() >= static_cast<int>(m.vertices_m.size())).any())
        throw InputError(who + ": a triangle index is out of range");
  }
}

}  // namespace crowdlab
