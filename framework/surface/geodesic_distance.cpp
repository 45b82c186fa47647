#include "framework/surface/geodesic_distance.hpp"

#include <cmath>
#include <limits>
#include <queue>

namespace crowdlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Triangle update (see header): distance at C from finalised A, B; kInf when not causal.
double triangle_update(const Vec3& A, const Vec3& B, const Vec3& C, double ta, double tb) {
  const Vec3 ab = B - A;
  const double c = ab.norm();
  if (c < 1e-12) return kInf;
  const Vec3 ex = ab / c;
  const Vec3 ac = C - A;
  const double cx = ac.dot(ex);
  const double cy = (ac - cx * ex).norm();
  if (cy < 1e-12) return kInf;
  const double sx = (ta * ta - tb * tb + c * c) / (2 * c);
  const double sy2 = ta * ta - sx * sx;
  if (sy2 < 0) return kInf;
  const double sy = -std::sqrt(sy2);
  // Where the ray S -> C crosses the line AB (y = 0).
  const double x_cross = sx + (cx - sx) * (-sy) / (cy - sy);
  if (x_cross < 0 || x_cross > c) return kInf;
  return std::hypot(cx - sx, cy - sy);
}

}  // namespace

std::vector<double> geodesic_distance_field(const SurfaceMesh& mesh, const std::vector<int>& sources) {
  const size_t V = mesh.vertices_m.size();
  std::vector<std::vector<int>> vertex_faces(V);
  for (int f = 0; f < mesh.face_count(); ++f)
    for (int k = 0; k < 3; ++k)
      vertex_faces[static_cast<size_t>(mesh.triangles[static_cast<size_t>(f)][k])].push_back(f);

  std::vector<double> dist(V, kInf);
  std::vector<char> done(V, 0);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
  for (int s : sources) {
    dist[static_cast<size_t>(s)] = 0.0;
    queue.emplace(0.0, s);
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (done[static_cast<size_t>(v)] || d > dist[static_cast<size_t>(v)]) continue;
    done[static_cast<size_t>(v)] = 1;
    for (int f : vertex_faces[static_cast<size_t>(v)]) {
      const Eigen::Vector3i& t = mesh.triangles[static_cast<size_t>(f)];
      for (int k = 0; k < 3; ++k) {
        const int x = t[k];
        if (done[static_cast<size_t>(x)]) continue;
        const Vec3& X = mesh.vertices_m[static_cast<size_t>(x)];
        double best = d + (X - mesh.vertices_m[static_cast<size_t>(v)]).norm();
        // The third corner w of this face: if finalised, try the triangle update from (v, w).
        const int w = t[0] + t[1] + t[2] - x - v;
        if (done[static_cast<size_t>(w)])
          best = std::min(best, triangle_update(mesh.vertices_m[static_cast<size_t>(v)],
                                                mesh.vertices_m[static_cast<size_t>(w)], X, d,
                                                dist[static_cast<size_t>(w)]));
        if (best < dist[static_cast<size_t>(x)]) {
          dist[static_cast<size_t>(x)] = best;
          queue.emplace(best, x);
        }
      }
    }
  }
  return dist;
}

Vec3 barycentric(const SurfaceMesh& mesh, int face, const Vec3& p) {
  const Vec3 a = mesh.corner(face, 0), v0 = mesh.corner(face, 1) - a, v1 = mesh.corner(face, 2) - a,
             v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1), d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double denom = d00 * d11 - d01 * d01;
  const double v = (d11 * d20 - d01 * d21) / denom, w = (d00 * d21 - d01 * d20) / denom;
  return Vec3(1.0 - v - w, v, w);
}

double interpolate_field(const SurfaceMesh& mesh, const std::vector<double>& field, int face, const Vec3& p) {
  const Vec3 b = barycentric(mesh, face, p);
  const Eigen::Vector3i& t = mesh.triangles[static_cast<size_t>(face)];
  return b[0] * field[static_cast<size_t>(t[0])] + b[1] * field[static_cast<size_t>(t[1])] +
         b[2] * field[static_cast<size_t>(t[2])];
}

Vec3 descent_direction(const SurfaceMesh& mesh, const std::vector<double>& field, int face) {
  const Eigen::Vector3i& t = mesh.triangles[static_cast<size_t>(face)];
  const double f0 = field[static_cast<size_t>(t[0])], f1 = field[static_cast<size_t>(t[1])],
               f2 = field[static_cast<size_t>(t[2])];
  if (!std::isfinite(f0) || !std::isfinite(f1) || !std::isfinite(f2)) return Vec3::Zero();
  // Gradient of the linear interpolant: sum_k f_k * grad(lambda_k), grad(lambda_k) = n x e_k / (2 area),
  // with e_k the edge opposite corner k (counter-clockwise).
  const Vec3 p0 = mesh.corner(face, 0), p1 = mesh.corner(face, 1), p2 = mesh.corner(face, 2);
  const Vec3 n = mesh.face_normals[static_cast<size_t>(face)];
  const double twice_area = (p1 - p0).cross(p2 - p0).norm();
  const Vec3 grad = (f0 * n.cross(p2 - p1) + f1 * n.cross(p0 - p2) + f2 * n.cross(p1 - p0)) / twice_area;
  const double len = grad.norm();
  return len > 1e-12 ? Vec3(-grad / len) : Vec3::Zero();
}

int nearest_vertex(const SurfaceMesh& mesh, const Vec3& p) {
  int best = 0;
  double best_d = kInf;
  for (size_t i = 0; i < mesh.vertices_m.size(); ++i) {
    const double d = (mesh.vertices_m[i] - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(i);
    }
  }
  return best;
}

}  // namespace crowdlab
