#pragma once
// Moving a point along a SurfaceMesh: the displacement is followed across triangle edges, and the
// remaining displacement and the velocity are rotated about each crossed edge onto the next triangle's
// plane ("wrapped"), so motion continues over creases, onto walls and around folds of any angle.
#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

/// Where one agent is on the surface.
struct SurfacePoint {
  int face = 0;                    ///< triangle the agent stands on
  Vec3 position_m = Vec3::Zero();  ///< world frame, on the triangle
  double up_sign = 1.0;            ///< +1: "up" is the face normal; -1: its opposite. Flips when crossing
                                   ///< an orientation-reversing edge (non-orientable surfaces).
  Vec3 up(const SurfaceMesh& m) const { return m.face_normals[static_cast<size_t>(face)] * up_sign; }
};

/// [in,out] point: moved by `displacement_m` (world frame, tangent to the current face; its normal
///          component is ignored) across as many triangles as needed (at most 256 crossings).
/// [in,out] velocity_mps: rotated along with the motion; on a boundary edge its outward component is
///          removed and the agent slides along the boundary.
void move_on_surface(const SurfaceMesh& mesh, SurfacePoint& point, Vec3 displacement_m, Vec3& velocity_mps);

/// Removes the component of v along the point's face normal (projects onto the tangent plane).
Vec3 to_tangent(const SurfaceMesh& mesh, int face, const Vec3& v);

}  // namespace crowdlab
