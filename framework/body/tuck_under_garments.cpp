#include "framework/body/tuck_under_garments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/triangle_tree.hpp"

namespace crowdlab {
namespace {

constexpr int kTuckPasses = 8;
/// A point under a hem: the hem lies within 26 degrees of straight along its normal (cos 26 = 0.9).
constexpr double kUnderHemCosine = 0.9;
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

/// The outer layers of one tuck step: their triangles, a closest-point tree over them and their rims. The
/// outer layers do not move while an inner one is tucked, so this is built once per step.
class Cover {
 public:
  Cover(const SkinnedMesh& mesh, const std::vector<SurfaceKind>& outer, double reach_m)
      : triangles_(layer_triangles(mesh, outer)),
        tree_(mesh.rest_vertices_m, triangles_),
        rim_(boundary_vertices(static_cast<int>(mesh.rest_vertices_m.size()), triangles_)),
        reach_m_(reach_m) {}

  bool empty() const { return triangles_.empty(); }

  /// Offset d of p in front of the outer layers along the unit outward normal n, NaN where they do not
  /// cover p (see the header). With `under_hem`, a point whose closest point lies on a rim counts too when
  /// the hem lies nearly straight in front of or behind it (|d| >= kUnderHemCosine of the distance), and
  /// *under_hem says so; without it such a point is NaN.
  double depth(const Vec3& p, const Vec3& n, bool* under_hem = nullptr) const {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    if (tree_.bounds().squared_distance(p) > reach_m_ * reach_m_) return kNaN;  // far from every garment
    const TriangleHit hit = tree_.closest(p);
    if (hit.triangle < 0 || hit.distance > reach_m_) return kNaN;
    const Eigen::Vector3i& t = triangles_[static_cast<size_t>(hit.triangle)];
    bool on_rim = true;
    for (int k = 0; k < 3; ++k)
      if (hit.barycentric[k] > 1e-9 && !rim_[static_cast<size_t>(t[k])]) on_rim = false;
    const double d = (hit.point - p).dot(n);
    if (on_rim) {
      if (under_hem == nullptr || std::abs(d) < kUnderHemCosine * hit.distance) return kNaN;  // beside a hem
      *under_hem = true;
      return d;
    }
    if (under_hem != nullptr) *under_hem = false;
    if (std::abs(d) < 0.5 * hit.distance) return kNaN;  // the garment lies beside the vertex
    return d;
  }

 private:
  std::vector<Eigen::Vector3i> triangles_;
  TriangleTree tree_;
  std::vector<bool> rim_;
  double reach_m_;
};

/// Outward unit normals of the inner layer's vertices (zero where its triangles do not use a vertex).
std::vector<Vec3> inner_normals(const SkinnedMesh& mesh, SurfaceKind inner) {
  return vertex_normals(mesh.rest_vertices_m, layer_triangles(mesh, {inner}));
}

bool used(const Vec3& normal) {
  return normal.squaredNorm() > 0.25;
}

/// One layer tucked under the outer ones; returns how many vertices moved.
int tuck_layer(SkinnedMesh& mesh, SurfaceKind inner, const std::vector<SurfaceKind>& outer, double margin_m,
               double reach_m = kTuckReachM) {
  const Cover cover(mesh, outer, reach_m);
  if (cover.empty()) return 0;
  std::vector<bool> moved(mesh.rest_vertices_m.size(), false);
  std::vector<Vec3> normal = inner_normals(mesh, inner);
  // A move turns the neighbours' normals, so what it leaves is measured again (a few passes settle it).
  for (int pass = 0; pass < kTuckPasses; ++pass) {
    if (pass > 0) normal = inner_normals(mesh, inner);
    bool any = false;
    for (size_t v = 0; v < normal.size(); ++v) {
      if (!used(normal[v])) continue;
      bool under_hem = false;
      const double d = cover.depth(mesh.rest_vertices_m[v], normal[v], &under_hem);
      const double margin = under_hem ? std::min(margin_m, kHemMarginM) : margin_m;
      if (!(d < margin - kTuckSettledM)) continue;  // NaN (not covered) or deep enough
      mesh.rest_vertices_m[v] += (d - margin) * normal[v];
      moved[v] = any = true;
    }
    if (!any) break;
  }
  return static_cast<int>(std::count(moved.begin(), moved.end(), true));
}

}  // namespace

std::vector<double> cover_depths(const SkinnedMesh& mesh, SurfaceKind inner,
                                 const std::vector<SurfaceKind>& outer, std::vector<Vec3>& normal,
                                 double reach_m, bool under_hems_only) {
  std::vector<double> depth(mesh.rest_vertices_m.size(), std::numeric_limits<double>::quiet_NaN());
  normal = inner_normals(mesh, inner);
  const Cover cover(mesh, outer, reach_m);
  if (cover.empty()) return depth;
  for (size_t v = 0; v < depth.size(); ++v) {
    if (!used(normal[v])) continue;
    bool under_hem = false;
    const double d = cover.depth(mesh.rest_vertices_m[v], normal[v], under_hems_only ? &under_hem : nullptr);
    if (under_hem || !under_hems_only) depth[v] = d;
  }
  return depth;
}

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
