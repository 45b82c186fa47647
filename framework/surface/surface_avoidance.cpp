#include "framework/surface/surface_avoidance.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "framework/surface/relevance.hpp"
#include "framework/surface/tangent_orca.hpp"

namespace crowdlab {
namespace {

/// At most three Offset tuples per neighbour, for up to 32 neighbours.
constexpr size_t kMaxOrcaLines = 3 * 32;

/// Social forces (see header): velocity after one explicit step of the force model.
Vec3 social_force_velocity(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i, size_t keep,
                           const Vec3& v_pref) {
  const SurfaceCrowdParams& p = model.params;
  const size_t K = static_cast<size_t>(p.max_neighbors);
  const Vec3& feet_a = s.points[i].position_m;
  const SocialForceParams& sf = p.social;
  Vec3 acc = (v_pref - s.velocity_mps[i]) / sf.relaxation_s;
  for (size_t k = 0; k < keep; ++k) {
    const size_t j = static_cast<size_t>(s.neighbors[i * K + k]);
    const auto tuples = offset_three_spheres(feet_a, s.up[i], s.points[j].position_m, s.up[j], p.body);
    const OffsetTuple* worst = &tuples[0];
    for (const auto& t : tuples)
      if (t.clearance_m < worst->clearance_m) worst = &t;
    const double magnitude =
        sf.A_n * std::exp(-worst->clearance_m / sf.B_m) + sf.k_body * std::max(0.0, -worst->clearance_m);
    acc -= worst->direction * (magnitude / sf.mass_kg);
  }
  return s.velocity_mps[i] + acc * p.dt_s;
}

/// ORCA in a's tangent plane over the union of the Offset tuples (see header).
Vec3 orca_velocity(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i, size_t keep,
                   const Vec3& v_pref, orca::Line* lines, orca::Line* scratch) {
  const SurfaceCrowdParams& p = model.params;
  const size_t K = static_cast<size_t>(p.max_neighbors);
  const Vec3& up = s.up[i];
  Vec3 e1, e2;
  tangent_basis(up, e1, e2);
  const auto in_plane = [&](const Vec3& x) { return Vec2(e1.dot(x), e2.dot(x)); };
  const Vec2 velocity = in_plane(s.velocity_mps[i]);
  const double diameter = 2 * p.body.sphere_radius_m;
  size_t n = 0;
  for (size_t k = 0; k < keep; ++k) {
    const size_t j = static_cast<size_t>(s.neighbors[i * K + k]);
    const auto tuples =
        offset_three_spheres(s.points[i].position_m, up, s.points[j].position_m, s.up[j], p.body);
    const Vec2 rel_vel = velocity - in_plane(s.velocity_mps[j]);
    Vec2 previous = Vec2::Zero();
    bool have_previous = false;
    for (const OffsetTuple& t : tuples) {
      if (t.direction.squaredNorm() == 0.0) continue;  // straight above/below: no tangent direction
      const Vec2 rel_pos = in_plane(t.direction) * (t.clearance_m + diameter);
      if (have_previous && (rel_pos - previous).squaredNorm() < 1e-12) continue;  // same disc again
      previous = rel_pos;
      have_previous = true;
      lines[n++] = orca_half_plane(rel_pos, rel_vel, velocity, diameter + 2 * p.orca_margin_m,
                                   p.orca_time_horizon_s, p.dt_s);
    }
  }
  const Vec2 v = solve_orca(lines, n, in_plane(v_pref), p.max_speed_mps, scratch);
  return e1 * v.x() + e2 * v.y();
}

class SocialForceAvoidance final : public SurfaceAvoidanceModel {
 public:
  Vec3 velocity(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i, size_t keep,
                const Vec3& v_pref) const override {
    return social_force_velocity(model, s, i, keep, v_pref);
  }
};

class OrcaAvoidance final : public SurfaceAvoidanceModel {
 public:
  Vec3 velocity(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i, size_t keep,
                const Vec3& v_pref) const override {
    std::array<orca::Line, kMaxOrcaLines> lines, scratch;
    return orca_velocity(model, s, i, keep, v_pref, lines.data(), scratch.data());
  }
};

}  // namespace

const SurfaceAvoidanceModel& surface_avoidance_model(SurfaceAvoidance kind) {
  static const SocialForceAvoidance social;
  static const OrcaAvoidance orca_model;
  if (kind == SurfaceAvoidance::kOrca) return orca_model;
  return social;
}

}  // namespace crowdlab
