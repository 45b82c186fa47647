#pragma once
// SurfaceMesh: a triangle mesh that agents walk on (seed 002), with the connectivity they need to
// cross from one triangle to the next.
//
// Arrays (immutable once built by make_surface_mesh):
//   vertices_m     (V)    vertex positions, world frame, metres
//   triangles      (F)    vertex indices, counter-clockwise seen from the side the normal points to
//   face_normals   (F)    unit normals from the winding
//   vertex_normals (V)    area-weighted mean of incident face normals (for rendering/orientation)
//   neighbors      (F x 3) the face across edge e of face f, where edge e joins corners e and (e+1)%3;
//                          -1 on a boundary edge
//   neighbor_edge  (F x 3) which edge of the neighbour is the shared one
//   flips_orientation (F x 3) true when the neighbour traverses the shared edge in the SAME direction,
//                          i.e. its winding is inconsistent with this face (a Möbius strip has one
//                          such edge loop); agents crossing it flip their notion of "up".
#include <array>
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

struct SurfaceMesh {
  std::string name;
  std::vector<Vec3> vertices_m;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Vec3> face_normals;
  std::vector<Vec3> vertex_normals;
  std::vector<std::array<int, 3>> neighbors;
  std::vector<std::array<int, 3>> neighbor_edge;
  std::vector<std::array<bool, 3>> flips_orientation;
  double total_area_m2 = 0.0;

  int face_count() const { return static_cast<int>(triangles.size()); }
  Vec3 corner(int face, int k) const {
    return vertices_m[static_cast<size_t>(triangles[static_cast<size_t>(face)][k])];
  }
  Vec3 centroid(int face) const { return (corner(face, 0) + corner(face, 1) + corner(face, 2)) / 3.0; }
};

/// Builds connectivity and normals.
/// Repairs (documented, applied silently): exact duplicate vertices are welded; triangles with a
/// repeated vertex index or area below 1e-12 m^2 are dropped.
/// Errors (InputError naming `source` and the face/edge): out-of-range indices, non-finite
/// coordinates, an edge shared by more than two triangles (non-manifold), an empty mesh.
SurfaceMesh make_surface_mesh(std::vector<Vec3> vertices_m, std::vector<Eigen::Vector3i> triangles,
                              const std::string& source);

/// Loads a Wavefront OBJ (v / f lines; polygons fan-triangulated; v/vt/vn indices accepted, negative
/// indices resolved). `scale` converts file units to metres. Errors name the file and line.
SurfaceMesh load_obj_surface(const std::string& path, double scale = 1.0);

}  // namespace crowdlab
