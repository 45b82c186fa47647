#include "framework/surface/surface_measures.hpp"

#include <algorithm>

#include "framework/core/capsule.hpp"
#include "framework/surface/geodesic_distance.hpp"

namespace crowdlab {

double distance_to_face(const SurfaceMesh& mesh, int face, const Vec3& p) {
  const Vec3 b = barycentric(mesh, face, p);
  const Vec3 n = mesh.face_normals[static_cast<size_t>(face)];
  const double plane = std::abs(n.dot(p - mesh.corner(face, 0)));
  if (b.minCoeff() >= -1e-9) return plane;
  // Outside the triangle: distance to the nearest edge.
  double best = 1e300;
  for (int e = 0; e < 3; ++e)
    best = std::min(
        best, segment_closest_points(mesh.corner(face, e), mesh.corner(face, (e + 1) % 3), p, p).distance_m);
  return best;
}

void accumulate_surface_measures(const SurfaceCrowdModel& model, const SurfaceCrowdState& s,
                                 const TriangleBvh& bvh, SurfaceCrowdMeasures& m, double range) {
  const SurfaceMesh& mesh = *model.mesh;
  const size_t N = s.points.size(), K = static_cast<size_t>(model.params.max_neighbors);
  for (size_t i = 0; i < N; ++i) {
    const SurfacePoint& a = s.points[i];
    m.max_distance_to_surface_m =
        std::max(m.max_distance_to_surface_m, distance_to_face(mesh, a.face, a.position_m));
    const Vec3 ca = body_center(model, a);
    bool colliding = false;
    for (size_t j = 0; j < N; ++j) {
      if (j == i) continue;
      const SurfacePoint& b = s.points[j];
      const Vec3 cb = body_center(model, b);
      if ((cb - ca).norm() > model.params.body.height_m + range + 0.5) continue;
      const double clearance = stacked_clearance(a.position_m, body_up(model, a), b.position_m,
                                                 body_up(model, b), model.params.body);
      if (clearance > range) continue;
      const bool reachable = !bvh.segment_hits(ca, cb);
      const auto first = s.neighbors.begin() + static_cast<long>(i * K);
      const bool relevant =
          std::find(first, first + s.neighbor_count[i], static_cast<int>(j)) != first + s.neighbor_count[i];
      if (!relevant && reachable) ++m.false_negatives;
      if (reachable && clearance < 0) colliding = true;
    }
    // False positives: every neighbour the avoidance model is given (at any distance) that it cannot
    // reach; it steers around each of them.
    for (int k = 0; k < s.neighbor_count[i]; ++k) {
      const SurfacePoint& b = s.points[static_cast<size_t>(s.neighbors[i * K + static_cast<size_t>(k)])];
      if (bvh.segment_hits(ca, body_center(model, b))) ++m.false_positives;
    }
    ++m.agent_frames;
    if (colliding) ++m.colliding_agent_frames;
  }
}

}  // namespace crowdlab
