#include "framework/surface/smooth_surface_up.hpp"

#include <algorithm>
#include <cmath>

#include "framework/surface/geodesic_distance.hpp"

namespace crowdlab {

Vec3 smooth_surface_up(const SurfaceMesh& mesh, const SurfacePoint& point) {
  const Vec3 face_up = point.up(mesh);
  const Vec3 b = barycentric(mesh, point.face, point.position_m);
  Vec3 n = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    const Vec3& vn =
        mesh.vertex_normals[static_cast<size_t>(mesh.triangles[static_cast<size_t>(point.face)][k])];
    n += std::clamp(b[k], 0.0, 1.0) * (vn.dot(face_up) < 0 ? Vec3(-vn) : vn);
  }
  const double len = n.norm();
  // cos(80 deg) = 0.1736: beyond it the blend is not a plausible standing direction.
  if (len < 1e-6 || n.dot(face_up) < 0.1736 * len) return face_up;
  return n / len;
}

}  // namespace crowdlab
