#include "framework/surface/surface_walk.hpp"

#include <cmath>

#include "framework/surface/geodesic_distance.hpp"

namespace crowdlab {

Vec3 to_tangent(const SurfaceMesh& mesh, int face, const Vec3& v) {
  const Vec3& n = mesh.face_normals[static_cast<size_t>(face)];
  return v - n * n.dot(v);
}

void move_on_surface(const SurfaceMesh& mesh, SurfacePoint& pt, Vec3 d, Vec3& velocity) {
  d = to_tangent(mesh, pt.face, d);
  velocity = to_tangent(mesh, pt.face, velocity);
  for (int hop = 0; hop < 256 && d.squaredNorm() > 1e-24; ++hop) {
    const int f = pt.face;
    const Vec3 b0 = barycentric(mesh, f, pt.position_m);
    const Vec3 db = barycentric(mesh, f, pt.position_m + d) - b0;
    // Earliest edge where a barycentric coordinate reaches zero while decreasing. Coordinate of corner
    // (e+2)%3 vanishes on edge e (corners e, e+1).
    double t_exit = 1.0;
    int exit_edge = -1;
    for (int e = 0; e < 3; ++e) {
      const int opposite = (e + 2) % 3;
      if (db[opposite] < -1e-12) {
        const double t = std::max(0.0, b0[opposite]) / -db[opposite];
        if (t < t_exit) {
          t_exit = t;
          exit_edge = e;
        }
      }
    }
    if (exit_edge < 0) {
      pt.position_m += d;
      break;
    }
    pt.position_m += t_exit * d;
    d *= (1.0 - t_exit);
    const Vec3 a = mesh.corner(f, exit_edge), b = mesh.corner(f, (exit_edge + 1) % 3);
    const Vec3 axis = (b - a).normalized();
    const int next = mesh.neighbors[static_cast<size_t>(f)][static_cast<size_t>(exit_edge)];
    if (next < 0) {
      // Boundary: keep only motion along the edge (slide), so the agent never leaves the mesh.
      d = axis * axis.dot(d);
      velocity = axis * axis.dot(velocity);
      if (d.squaredNorm() < 1e-24) break;
      // Avoid re-detecting the same edge at t = 0 by stepping along it in this face.
      continue;
    }
    // Rotate about the shared edge from this face's plane onto the next one.
    const Vec3 n0 = mesh.face_normals[static_cast<size_t>(f)],
               n1 = mesh.face_normals[static_cast<size_t>(next)];
    const bool flip = mesh.flips_orientation[static_cast<size_t>(f)][static_cast<size_t>(exit_edge)];
    // With inconsistent winding the neighbour's stored normal points to the other side: compare
    // against its oriented version so the fold angle is the geometric one.
    const Vec3 n1_oriented = flip ? Vec3(-n1) : n1;
    const double angle = std::atan2(n0.cross(n1_oriented).dot(axis), n0.dot(n1_oriented));
    const Eigen::AngleAxisd rot(angle, axis);
    d = rot * d;
    velocity = rot * velocity;
    if (flip) pt.up_sign = -pt.up_sign;
    pt.face = next;
  }
  // Remove round-off drift off the plane of the final face.
  const Vec3& n = mesh.face_normals[static_cast<size_t>(pt.face)];
  pt.position_m -= n * n.dot(pt.position_m - mesh.corner(pt.face, 0));
  velocity = to_tangent(mesh, pt.face, velocity);
}

}  // namespace crowdlab
