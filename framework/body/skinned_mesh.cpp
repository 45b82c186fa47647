#include "framework/body/skinned_mesh.hpp"

namespace crowdlab {

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
