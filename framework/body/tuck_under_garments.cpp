#include "framework/body/tuck_under_garments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/triangle_tree.hpp"

namespace crowdlab {
namespace {

constexpr int kTuckPasses = 8;
constexpr double kTuckSettledM = 1e-4;  // a vertex this close to its depth stays

bool is_one_of(std::uint8_t s, const std::vector<SurfaceKind>& kinds) {
  return std::any_of(kinds.begin(), kinds.end(),
                     [&](SurfaceKind k) { return s == static_cast<std::uint8_t>(k); });
}

/// The triangles whose three vertices all carry one of `kinds`.
std::vector<Eigen::Vector3i> layer_triangles(const SkinnedMesh& mesh, const std::vector<SurfaceKind>& kinds) {
  std::vector<Eigen::Vector3i> out;
  for (const Eigen::Vector3i& t : mesh.triangles)
    if (is_one_of(mesh.surface[static_cast<size_t>(t[0])], kinds) &&
        is_one_of(mesh.surface[static_cast<size_t>(t[1])], kinds) &&
        is_one_of(mesh.surface[static_cast<size_t>(t[2])], kinds))
      out.push_back(t);
  return out;
}

}  // namespace

std::vector<double> cover_depths(const SkinnedMesh& mesh, SurfaceKind inner,
                                 const std::vector<SurfaceKind>& outer, std::vector<Vec3>& normal,
                                 double reach_m) {
  const size_t n = mesh.rest_vertices_m.size();
  std::vector<double> depth(n, std::numeric_limits<double>::quiet_NaN());
  const std::vector<Eigen::Vector3i> inner_tris = layer_triangles(mesh, {inner});
  const std::vector<Eigen::Vector3i> outer_tris = layer_triangles(mesh, outer);
  if (inner_tris.empty() || outer_tris.empty()) return depth;
  normal = vertex_normals(mesh.rest_vertices_m, inner_tris);
  const TriangleTree tree(mesh.rest_vertices_m, outer_tris);
  const std::vector<bool> rim = boundary_vertices(static_cast<int>(n), outer_tris);
  for (size_t v = 0; v < n; ++v) {
    if (normal[v].squaredNorm() < 0.25) continue;  // not used by the inner layer's triangles
    const Vec3& p = mesh.rest_vertices_m[v];
    const TriangleHit hit = tree.closest(p);
    if (hit.triangle < 0 || hit.distance > reach_m) continue;
    const Eigen::Vector3i& t = outer_tris[static_cast<size_t>(hit.triangle)];
    bool on_rim = true;
    for (int k = 0; k < 3; ++k)
      if (hit.barycentric[k] > 1e-9 && !rim[static_cast<size_t>(t[k])]) on_rim = false;
    if (on_rim) continue;  // beside a hem, not under it
    const double d = (hit.point - p).dot(normal[v]);
    if (std::abs(d) < 0.5 * hit.distance) continue;  // the garment lies beside the vertex
    depth[v] = d;
  }
  return depth;
}

namespace {

/// One layer tucked under the outer ones; returns how many vertices moved.
int tuck_layer(SkinnedMesh& mesh, SurfaceKind inner, const std::vector<SurfaceKind>& outer, double margin_m,
               double reach_m = kTuckReachM) {
  std::vector<bool> moved(mesh.rest_vertices_m.size(), false);
  // A move turns the neighbours' normals, so what it leaves is measured again (a few passes settle it).
  for (int pass = 0; pass < kTuckPasses; ++pass) {
    std::vector<Vec3> normal;
    const std::vector<double> depth = cover_depths(mesh, inner, outer, normal, reach_m);
    bool any = false;
    for (size_t v = 0; v < depth.size(); ++v) {
      if (!(depth[v] < margin_m - kTuckSettledM)) continue;  // NaN (not covered) or deep enough
      mesh.rest_vertices_m[v] += (depth[v] - margin_m) * normal[v];
      moved[v] = any = true;
    }
    if (!any) break;
  }
  return static_cast<int>(std::count(moved.begin(), moved.end(), true));
}

}  // namespace

int tuck_under_garments(SkinnedMesh& mesh, double margin_m) {
  if (mesh.surface.size() != mesh.rest_vertices_m.size()) return 0;
  int moved = tuck_layer(mesh, SurfaceKind::kLowerGarment, {SurfaceKind::kUpperGarment}, margin_m);
  moved += tuck_layer(mesh, SurfaceKind::kShoes, {SurfaceKind::kLowerGarment}, margin_m);
  moved +=
      tuck_layer(mesh, SurfaceKind::kSkin,
                 {SurfaceKind::kUpperGarment, SurfaceKind::kLowerGarment, SurfaceKind::kShoes}, margin_m);
  // Legs swing inside a skirt: the thighs under it go deeper (see the header).
  moved += tuck_layer(mesh, SurfaceKind::kSkin, {SurfaceKind::kLowerGarment}, kSkirtMarginM, kSkirtReachM);
  return moved;
}

}  // namespace crowdlab
