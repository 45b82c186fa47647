#include "framework/surface/relevance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/error.hpp"

namespace crowdlab {

bool segment_pierces_disk(const Vec3& p, const Vec3& q, const Vec3& centre, const Vec3& normal,
                          double radius) {
  const double dp = normal.dot(p - centre), dq = normal.dot(q - centre);
  if ((dp > 0) == (dq > 0) || dp == dq) return false;  // both on one side: no crossing of the plane
  const double t = dp / (dp - dq);
  if (t <= 0.0 || t > 1.0) return false;
  const Vec3 hit = p + t * (q - p);
  return (hit - centre).squaredNorm() <= radius * radius;
}

bool mutually_visible(const Vec3& feet_a, const Vec3& normal_a, const Vec3& feet_b, const Vec3& normal_b,
                      const Vec3& head_b) {
  const Vec3 from = feet_a + normal_a * kEyeLift;
  return !segment_pierces_disk(from, head_b, feet_b, normal_b, kFeetDiskRadius) &&
         !segment_pierces_disk(from, head_b, feet_a, normal_a, kFeetDiskRadius);
}

const char* relevant_mode_name(RelevantMode m) {
  switch (m) {
    case RelevantMode::kVisibility:
      return "visibility";
    case RelevantMode::kVisibilityMesh:
      return "visibility_mesh";
    case RelevantMode::kEuclidean:
      return "euclidean";
    case RelevantMode::kSurface:
      return "surface";
  }
  return "?";
}

RelevantMode parse_relevant_mode(const std::string& text, const std::string& key) {
  for (RelevantMode m : {RelevantMode::kVisibility, RelevantMode::kVisibilityMesh, RelevantMode::kEuclidean,
                         RelevantMode::kSurface})
    if (text == relevant_mode_name(m)) return m;
  throw InputError(SourceLocation{"", 0, 0, key},
                   "must be visibility, visibility_mesh, euclidean or surface, not '" + text + "'");
}

namespace {
/// The part of segment p -> q inside the ball (centre, radius) hits the mesh.
bool segment_hits_within_ball(const Vec3& p, const Vec3& q, const Vec3& centre, double radius,
                              const TriangleBvh& bvh) {
  // |p + t d - c|^2 = r^2  <=>  a t^2 + 2 b t + c0 = 0
  const Vec3 d = q - p, m = p - centre;
  const double a = d.squaredNorm(), b = m.dot(d), c0 = m.squaredNorm() - radius * radius;
  const double disc = b * b - a * c0;
  if (a <= 0 || disc <= 0) return false;
  const double root = std::sqrt(disc);
  const double t0 = std::max(0.0, (-b - root) / a), t1 = std::min(1.0, (-b + root) / a);
  if (t1 <= t0) return false;
  return bvh.segment_hits(p + t0 * d, p + t1 * d);
}
}  // namespace

bool mutually_visible_near_feet(const Vec3& feet_a, const Vec3& normal_a, const Vec3& feet_b,
                                const Vec3& head_b, const TriangleBvh& bvh) {
  const Vec3 from = feet_a + normal_a * kEyeLift;
  return !segment_hits_within_ball(from, head_b, feet_b, kFeetDiskRadius, bvh) &&
         !segment_hits_within_ball(from, head_b, feet_a, kFeetDiskRadius, bvh);
}

std::array<OffsetTuple, 3> offset_three_spheres(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_o,
                                                const Vec3& up_o, const StackedBody& body) {
  std::array<OffsetTuple, 3> out;
  for (int i = 0; i < 3; ++i) {
    const Vec3 c_o = body.sphere_center(feet_o, up_o, i);
    // a's nearest sphere to this obstacle sphere.
    double best = std::numeric_limits<double>::infinity();
    Vec3 best_vec = Vec3::Zero();
    for (int j = 0; j < 3; ++j) {
      const Vec3 v = c_o - body.sphere_center(feet_a, up_a, j);
      if (v.squaredNorm() < best) {
        best = v.squaredNorm();
        best_vec = v;
      }
    }
    const Vec3 tangent = best_vec - up_a * up_a.dot(best_vec);
    const double tl = tangent.norm();
    out[static_cast<size_t>(i)].direction = tl > 1e-9 ? Vec3(tangent / tl) : Vec3::Zero();
    out[static_cast<size_t>(i)].clearance_m = std::sqrt(best) - 2 * body.sphere_radius_m;
  }
  return out;
}

double stacked_clearance(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_b, const Vec3& up_b,
                         const StackedBody& body) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      best = std::min(
          best, (body.sphere_center(feet_a, up_a, i) - body.sphere_center(feet_b, up_b, j)).squaredNorm());
  return std::sqrt(best) - 2 * body.sphere_radius_m;
}

}  // namespace crowdlab
