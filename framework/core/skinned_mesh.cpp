#include "framework/core/skinned_mesh.hpp"

#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab {

void validate_skinned_mesh(const SkinnedMesh& mesh, const std::string& context) {
  const std::string where = context + ": body mesh: ";
  const size_t n = mesh.rest_vertices_m.size();
  if (n == 0 || mesh.triangles.empty()) throw InputError(where + "no vertices or no triangles");
  if (mesh.rest_normals.size() != n || mesh.joints.size() != n || mesh.weights.size() != n ||
      mesh.region.size() != n)
    throw InputError(where + "normals, joints, weights and regions must have one entry per vertex (" +
                     std::to_string(n) + ")");
  for (size_t i = 0; i < n; ++i) {
    // The message is built only when a vertex fails: building it for each of a body's ~15,000 vertices
    // was most of what reading a crowd file spent here (issue 31).
    const auto fail = [&](const std::string& what) {
      throw InputError(where + "vertex " + std::to_string(i) + ": " + what);
    };
    if (!mesh.rest_vertices_m[i].allFinite() || !mesh.rest_normals[i].allFinite())
      fail("position or normal is not finite");
    double total = 0.0;
    for (size_t k = 0; k < 4; ++k) {
      const double w = mesh.weights[i][k];
      if (!std::isfinite(w) || w < 0.0) fail("weight is negative or not finite");
      if (mesh.joints[i][k] < 0 || mesh.joints[i][k] >= kJointCount)
        fail("joint index " + std::to_string(mesh.joints[i][k]) + " outside [0, 24)");
      total += w;
    }
    if (std::abs(total - 1.0) > 1e-4) fail("weights sum to " + std::to_string(total));
    if (mesh.region[i] < 0 || mesh.region[i] >= kJointCount)
      fail("region " + std::to_string(mesh.region[i]) + " outside [0, 24)");
  }
  if (!mesh.surface.empty() && mesh.surface.size() != n)
    throw InputError(where + "surface labels must be empty or one per vertex (" + std::to_string(n) + ")");
  for (size_t i = 0; i < mesh.surface.size(); ++i)
    if (mesh.surface[i] >= static_cast<std::uint8_t>(SurfaceKind::kCount))
      throw InputError(where + "vertex " + std::to_string(i) + ": surface label " +
                       std::to_string(mesh.surface[i]) + " is unknown");
  for (size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] < 0 || static_cast<size_t>(mesh.triangles[t][k]) >= n)
        throw InputError(where + "triangle " + std::to_string(t) + " has an index outside [0, " +
                         std::to_string(n) + ")");
  for (const Vec3& p : mesh.rest_joints_m)
    if (!p.allFinite()) throw InputError(where + "a rest joint position is not finite");
}

std::vector<Vec3> skin_vertices(const SkinnedMesh& mesh, const BoneTransforms& bones) {
  std::vector<Vec3> out(mesh.rest_vertices_m.size(), Vec3::Zero());
  for (size_t i = 0; i < out.size(); ++i) {
    const Vec3& v = mesh.rest_vertices_m[i];
    for (size_t k = 0; k < 4; ++k) {
      const double w = mesh.weights[i][k];
      if (w <= 0.0) continue;
      const auto j = static_cast<size_t>(mesh.joints[i][k]);
      out[i] += w * bones[j].apply(v - mesh.rest_joints_m[j]);
    }
  }
  return out;
}

std::vector<Vec3> vertex_normals(const std::vector<Vec3>& vertices,
                                 const std::vector<Eigen::Vector3i>& triangles) {
  std::vector<Vec3> n(vertices.size(), Vec3::Zero());
  for (const auto& t : triangles) {
    const Vec3& a = vertices[static_cast<size_t>(t[0])];
    const Vec3 face =
        (vertices[static_cast<size_t>(t[1])] - a).cross(vertices[static_cast<size_t>(t[2])] - a);
    for (int k = 0; k < 3; ++k) n[static_cast<size_t>(t[k])] += face;  // |face| = 2 * area
  }
  for (Vec3& v : n)
    if (v.norm() > 0.0) v.normalize();
  return n;
}

double mesh_volume(const std::vector<Vec3>& vertices, const std::vector<Eigen::Vector3i>& triangles) {
  double six_v = 0.0;
  for (const auto& t : triangles)
    six_v += vertices[static_cast<size_t>(t[0])].dot(
        vertices[static_cast<size_t>(t[1])].cross(vertices[static_cast<size_t>(t[2])]));
  return six_v / 6.0;
}

}  // namespace crowdlab
