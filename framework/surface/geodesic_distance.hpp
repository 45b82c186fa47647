#pragma once
// Geodesic distance fields on a SurfaceMesh, computed once per goal (seed 002 navigates toward goals on
// the mesh; the paper leaves the method open, we use fast marching).
//
// Method: fast marching on triangle meshes (Kimmel & Sethian 1998, PNAS 95:8431): vertices are
// finalised in order of distance like Dijkstra; a vertex's tentative distance is the minimum of
//   - edge updates  T_v + |v - x|  (Dijkstra, an upper bound), and
//   - triangle updates from two finalised corners A, B: the virtual point source S in the triangle's
//     plane with |S-A| = T_A, |S-B| = T_B (on the far side of AB) gives T_C = |S - C| when the ray S->C
//     crosses edge AB (causality); otherwise the edge updates stand.
// Exact for planar wavefronts; on flat meshes the error is far below the edge-only Dijkstra error (which
// overestimates diagonal distances by up to ~8 % on a regular grid).
#include <vector>

#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

/// [in]  mesh, source_vertices (indices with distance 0)
/// [out] per-vertex geodesic distance in metres (+inf where unreachable: another component)
std::vector<double> geodesic_distance_field(const SurfaceMesh& mesh, const std::vector<int>& source_vertices);

/// The unit direction of steepest descent of a per-vertex field within `face`, in the face plane
/// (world frame). Zero when the field is flat or infinite there.
Vec3 descent_direction(const SurfaceMesh& mesh, const std::vector<double>& field, int face);

/// Linear interpolation of a per-vertex field at a point of `face` (world frame).
double interpolate_field(const SurfaceMesh& mesh, const std::vector<double>& field, int face,
                         const Vec3& point_m);

/// Barycentric coordinates of `point_m` with respect to face corners 0, 1, 2 (point projected to the plane).
Vec3 barycentric(const SurfaceMesh& mesh, int face, const Vec3& point_m);

/// The vertex nearest to a point (linear scan; used once per goal).
int nearest_vertex(const SurfaceMesh& mesh, const Vec3& point_m);

}  // namespace crowdlab
