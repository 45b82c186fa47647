#include "framework/body/cover_capsules.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/point_capsule_distance.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kReportTolerance_m = 0.005;  // the coverage tolerance, for within_before/after
constexpr double kMinRadius_m = 0.01;
constexpr double kMaxShift_m = 0.08;

/// Share of `vertices` within tolerance of the capsules.
double share_within(const std::vector<Vec3>& vertices, const WorldCapsules& caps, double tolerance_m) {
  if (vertices.empty()) return 1.0;
  long within = 0;
  for (const Vec3& v : vertices) {
    double d = 1e300;
    for (const Capsule& c : caps) d = std::min(d, point_capsule_distance(v, c));
    if (d <= tolerance_m) ++within;
  }
  return static_cast<double>(within) / static_cast<double>(vertices.size());
}

/// Tolerance of every vertex (+infinity: not bounded).
std::vector<double> vertex_tolerances(const SkinnedMesh& mesh, const std::vector<Vec3>& vertices,
                                      const SurfaceTolerances& tol) {
  double lowest = kInf;
  for (const Vec3& v : vertices) lowest = std::min(lowest, v.y());
  std::vector<double> out(vertices.size(), tol.tolerance_m[static_cast<size_t>(SurfaceKind::kSkin)]);
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (mesh.surface.empty()) continue;  // a bare skin: every vertex is skin
    const auto kind =
        static_cast<SurfaceKind>(std::min<int>(mesh.surface[v], static_cast<int>(SurfaceKind::kCount) - 1));
    out[v] = tol.tolerance_m[static_cast<size_t>(kind)];
    if (kind == SurfaceKind::kShoes && tol.sole_height_m >= 0.0 &&
        vertices[v].y() - lowest <= tol.sole_height_m)
      out[v] = kInf;
  }
  return out;
}

/// The radius capsule c (its own radius ignored) needs to take in the points within their tolerances.
double needed_radius(const Capsule& c, const std::vector<const Vec3*>& points,
                     const std::vector<double>& tol) {
  Capsule axis = c;
  axis.radius_m = 0.0;
  double r = 0.0;
  for (size_t k = 0; k < points.size(); ++k)
    r = std::max(r, point_capsule_distance(*points[k], axis) - tol[k]);
  return r;
}

/// A bone's fitted capsule: the axis translation, the radius, and how far (m) the farthest of its
/// points stays beyond its tolerance (0 unless the floor cap stopped the radius).
struct BoneFit {
  Vec3 shift = Vec3::Zero();
  double radius_m = 0.0;
  double miss_m = 0.0;
};

/// Capsule c moved by d, fitted to the points: the radius they need, at most the floor cap (the axis's
/// lowest end's height above floor_y, or the unfitted radius when that is larger) when floor_y is finite.
BoneFit fit_at(const Capsule& c, const Vec3& d, const std::vector<const Vec3*>& points,
               const std::vector<double>& tol, double floor_y) {
  const Capsule moved{c.a + d, c.b + d, 0.0};
  BoneFit f{d, std::max(kMinRadius_m, needed_radius(moved, points, tol) + 1e-9), 0.0};
  if (std::isfinite(floor_y)) {
    const double cap = std::max(std::min(moved.a.y(), moved.b.y()) - floor_y, c.radius_m);
    f.miss_m = std::max(0.0, f.radius_m - cap);
    f.radius_m = std::min(f.radius_m, cap);
  }
  return f;
}

/// The axis translation (perpendicular to the axis, |d| <= kMaxShift_m) that first minimises the miss and
/// then the radius, on a 2 cm grid and then a 5 mm grid around its best point.
BoneFit best_fit(const Capsule& c, const std::vector<const Vec3*>& points, const std::vector<double>& tol,
                 double floor_y) {
  const Vec3 dir = (c.b - c.a).norm() > 1e-9 ? Vec3((c.b - c.a).normalized()) : Vec3::UnitY();
  const Vec3 u = any_perpendicular(dir).normalized(), w = dir.cross(u).normalized();
  BoneFit best = fit_at(c, Vec3::Zero(), points, tol, floor_y);
  auto better = [](const BoneFit& x, const BoneFit& y) {
    return x.miss_m < y.miss_m - 1e-9 || (x.miss_m <= y.miss_m + 1e-9 && x.radius_m < y.radius_m - 1e-9);
  };
  for (const double step : {0.02, 0.005}) {
    const Vec3 centre = best.shift;
    for (int i = -4; i <= 4; ++i)
      for (int k = -4; k <= 4; ++k) {
        const Vec3 d = centre + step * (i * u + k * w);
        if (d.norm() > kMaxShift_m || (i == 0 && k == 0)) continue;
        const BoneFit f = fit_at(c, d, points, tol, floor_y);
        if (better(f, best)) best = f;
      }
  }
  return best;
}

}  // namespace

SurfaceTolerances SurfaceTolerances::uniform(double tol_m) {
  SurfaceTolerances t;
  t.tolerance_m.fill(tol_m);
  return t;
}

SurfaceTolerances SurfaceTolerances::per_surface() {
  SurfaceTolerances t = uniform(0.005);
  t.tolerance_m[static_cast<size_t>(SurfaceKind::kHair)] = 0.02;
  t.sole_height_m = 0.015;
  return t;
}

CoverReport fit_capsules_to_mesh(BodyShape& shape, const SkinnedMesh& mesh,
                                 const SurfaceTolerances& tolerances, bool move_axes) {
  CoverReport report;
  const Pose rest = Pose::rest(shape);
  const BoneTransforms bones = forward_kinematics(shape, rest);
  // The mesh's rest frame is the rest pose's (core/skinned_mesh.hpp): skinning it there is the identity up to
  // the root's placement, which this makes exact.
  const std::vector<Vec3> vertices = skin_vertices(mesh, bones);
  const std::vector<double> tol = vertex_tolerances(mesh, vertices, tolerances);
  const WorldCapsules caps = world_capsules(shape, bones);
  report.within_before = share_within(vertices, caps, kReportTolerance_m);
  // Each bounded vertex to the capsule it is nearest the surface of.
  std::array<std::vector<const Vec3*>, kJointCount> points;
  std::array<std::vector<double>, kJointCount> point_tol;
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (!std::isfinite(tol[v])) continue;
    size_t best = 0;
    double best_d = 1e300;
    for (size_t j = 0; j < kJointCount; ++j) {
      const double d = point_capsule_distance(vertices[v], caps[j]);
      if (d < best_d) {
        best_d = d;
        best = j;
      }
    }
    points[best].push_back(&vertices[v]);
    point_tol[best].push_back(tol[v]);
  }
  double floor_y = kInf;  // the rest pose's lowest vertex: the capsules may not reach below it
  if (tolerances.keep_above_floor)
    for (const Vec3& v : vertices) floor_y = std::min(floor_y, v.y());
  WorldCapsules fitted = caps;
  for (size_t j = 0; j < kJointCount; ++j) {
    const Capsule& c = caps[j];
    // 1 nm more, so that the round-off of recomputing the distance cannot leave a vertex a hair outside.
    // Radii only: grow, never shrink.
    BoneFit fit = fit_at(c, Vec3::Zero(), points[j], point_tol[j], floor_y);
    fit.radius_m = std::max(fit.radius_m, c.radius_m);
    if (move_axes && !points[j].empty()) fit = best_fit(c, points[j], point_tol[j], floor_y);
    // The shift in bone j's frame (world_capsules applies the bone's rest rotation).
    const Vec3 local_shift = bones[j].rotation.conjugate() * fit.shift;
    report.growth_m[j] = fit.radius_m - shape.capsules[j].radius_m;
    report.shift_m[j] = fit.shift.norm();
    report.floor_miss_m[j] = fit.miss_m;
    shape.capsules[j].a += local_shift;
    shape.capsules[j].b += local_shift;
    shape.capsules[j].radius_m = fit.radius_m;
    fitted[j] = {c.a + fit.shift, c.b + fit.shift, fit.radius_m};
  }
  compute_rest_contact_pairs(shape);
  report.within_after = share_within(vertices, fitted, kReportTolerance_m);
  long bounded = 0, within = 0;
  for (size_t v = 0; v < vertices.size(); ++v) {
    if (!std::isfinite(tol[v])) continue;
    ++bounded;
    double d = 1e300;
    for (const Capsule& c : fitted) d = std::min(d, point_capsule_distance(vertices[v], c));
    within += d <= tol[v] + 1e-9;
  }
  report.bounded_within_after =
      bounded > 0 ? static_cast<double>(within) / static_cast<double>(bounded) : 1.0;
  return report;
}

CoverReport cover_mesh_with_capsules(BodyShape& shape, const SkinnedMesh& mesh, double tolerance_m) {
  return fit_capsules_to_mesh(shape, mesh, SurfaceTolerances::uniform(tolerance_m), false);
}

}  // namespace crowdlab
