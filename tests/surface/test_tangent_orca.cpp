// ORCA in the tangent plane (tangent_orca.hpp): the reciprocal half-planes keep any two agents that
// respect them collision-free over the horizon (van den Berg et al. 2011, Theorem/Sec. 4), and surface
// agents that avoid with ORCA do not overlap.
#include <catch2/catch.hpp>

#include "framework/core/seed.hpp"
#include "framework/surface/geodesic_distance.hpp"
#include "framework/surface/surface_crowd.hpp"
#include "framework/surface/surface_measures.hpp"
#include "framework/surface/surface_scenes.hpp"
#include "framework/surface/tangent_orca.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_tangent_orca {

using namespace crowdlab;

namespace {
/// Smallest distance between two discs' centres over t in [0, tau] for relative position p and
/// relative velocity v (closest approach of p - v t).
double min_distance(const Vec2& p, const Vec2& v, double tau) {
  const double t = v.squaredNorm() > 0 ? std::clamp(p.dot(v) / v.squaredNorm(), 0.0, tau) : 0.0;
  return (p - v * t).norm();
}
}  // namespace

TEST_CASE("tangent basis is orthonormal and right-handed about up") {
  Rng rng(derive_seed(7, "basis"));
  for (int k = 0; k < 200; ++k) {
    const Vec3 up = Vec3(standard_normal(rng), standard_normal(rng), standard_normal(rng)).normalized();
    Vec3 e1, e2;
    tangent_basis(up, e1, e2);
    CHECK(e1.norm() == Approx(1).margin(1e-12));
    CHECK(e2.norm() == Approx(1).margin(1e-12));
    CHECK(std::abs(e1.dot(up)) < 1e-12);
    CHECK(std::abs(e1.dot(e2)) < 1e-12);
    CHECK((e1.cross(e2) - up).norm() < 1e-12);
  }
}

TEST_CASE("two agents that each respect their ORCA half-plane do not collide within the horizon") {
  Rng rng(derive_seed(11, "orca-pairs"));
  const double R = 0.5, tau = 2.0, dt = 0.1;
  int constrained = 0;
  for (int k = 0; k < 2000; ++k) {
    const Vec2 pa(0, 0), pb(4 * uniform01(rng) - 2, 4 * uniform01(rng) - 2);
    if ((pb - pa).norm() <= R * 1.01) continue;  // the theorem is about agents not yet overlapping
    const Vec2 va(2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1),
        vb(2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1);
    const orca::Line la = orca_half_plane(pb - pa, va - vb, va, R, tau, dt);
    const orca::Line lb = orca_half_plane(pa - pb, vb - va, vb, R, tau, dt);
    // Each picks the velocity closest to a random preference that satisfies its own half-plane.
    const Vec2 want_a(2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1),
        want_b(2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1);
    orca::Line scratch[1];
    const Vec2 na = solve_orca(&la, 1, want_a, 100.0, scratch);
    const Vec2 nb = solve_orca(&lb, 1, want_b, 100.0, scratch);
    if (min_distance(pb - pa, want_a - want_b, tau) < R) ++constrained;
    INFO("case " << k << " p " << (pb - pa).transpose() << " va " << va.transpose() << " vb "
                 << vb.transpose());
    CHECK(min_distance(pb - pa, na - nb, tau) >= R * (1 - 1e-6));
  }
  CHECK(constrained > 100);  // the property was exercised on many colliding preferences
}

TEST_CASE("ORCA agents crossing on a floor reach their antipodes without overlapping") {
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_ceiling_slab(10, 0.2, 0.25));
  SurfaceCrowdParams p;
  p.avoidance = SurfaceAvoidance::kOrca;
  // Eight agents on a circle on the top face, each heading for its antipode.
  SurfaceCrowdModel model = make_surface_crowd_model(mesh, p, 1, 3);
  SurfaceCrowdState s;
  model.goal_vertices.clear();
  model.goal_fields.clear();
  const int n = 8;
  for (int i = 0; i < n; ++i) {
    // Slightly irregular angles: a perfectly symmetric circle is a known ORCA deadlock (every agent's
    // best velocity is blocked the same way), which real crowds never present.
    const double a = 2 * M_PI * i / n + 0.2 * std::sin(1.7 * i);
    const Vec3 start(3.5 * std::cos(a), 2.7, 3.5 * std::sin(a)),
        goal(-4 * std::cos(a), 2.7, -4 * std::sin(a));
    int face = -1;
    for (int f = 0; f < mesh->face_count() && face < 0; ++f)
      if (distance_to_face(*mesh, f, start) < 1e-9) face = f;
    REQUIRE(face >= 0);
    s.points.push_back(SurfacePoint{face, start, 1.0});
    s.velocity_mps.push_back(Vec3::Zero());
    model.goal_vertices.push_back(nearest_vertex(*mesh, goal));
    model.goal_fields.push_back(geodesic_distance_field(*mesh, {model.goal_vertices.back()}));
    s.goal.push_back(i);
  }
  double worst = 1e9;
  std::vector<double> closest_to_goal(n, 1e9);
  for (int k = 0; k < 600; ++k) {
    step_surface_crowd(model, s);
    for (int i = 0; i < n; ++i)
      closest_to_goal[size_t(i)] =
          std::min(closest_to_goal[size_t(i)],
                   interpolate_field(*mesh, model.goal_fields[size_t(i)], s.points[size_t(i)].face,
                                     s.points[size_t(i)].position_m));
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        worst = std::min(
            worst, stacked_clearance(s.points[size_t(i)].position_m, s.points[size_t(i)].up(*mesh),
                                     s.points[size_t(j)].position_m, s.points[size_t(j)].up(*mesh), p.body));
  }
  INFO("smallest clearance " << worst);
  CHECK(worst > -0.01);  // ORCA: no overlap deeper than 1 cm (lp3 may concede a little in the jam)
  // Everybody got across (the crowd did not freeze): each came within a metre of its antipode.
  for (int i = 0; i < n; ++i) CHECK(closest_to_goal[size_t(i)] < 1.0);
}

}  // namespace test_tangent_orca
