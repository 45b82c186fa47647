// Properties of the core geometry: segment closest points and capsule contacts.
#include <catch2/catch.hpp>
#include <random>

#include "framework/core/capsule.hpp"
#include "framework/core/closest_approach.hpp"
#include "framework/core/seed.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_geometry {

using namespace crowdlab;

namespace {
// Brute-force reference: dense sampling of both segments.
double brute_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  double best = 1e300;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j <= 200; ++j) {
      const Vec3 a = p0 + (p1 - p0) * (i / 200.0), b = q0 + (q1 - q0) * (j / 200.0);
      best = std::min(best, (a - b).norm());
    }
  return best;
}
}  // namespace

TEST_CASE("segment closest points match brute force on random segments") {
  Rng rng(7);
  auto rnd = [&] { return Vec3(standard_normal(rng), standard_normal(rng), standard_normal(rng)); };
  for (int k = 0; k < 60; ++k) {
    const Vec3 p0 = rnd(), p1 = rnd(), q0 = rnd(), q1 = rnd();
    const auto cp = segment_closest_points(p0, p1, q0, q1);
    CHECK(cp.distance_m <= brute_distance(p0, p1, q0, q1) + 1e-9);
    CHECK(cp.distance_m >= brute_distance(p0, p1, q0, q1) - 2e-2);
    CHECK(cp.s >= 0.0);
    CHECK(cp.s <= 1.0);
    CHECK(cp.t >= 0.0);
    CHECK(cp.t <= 1.0);
  }
}

TEST_CASE("segment closest points are robust for parallel and degenerate segments") {
  // Parallel, overlapping: distance is the offset, point in the overlap.
  auto cp = segment_closest_points({0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 1, 0});
  CHECK(cp.distance_m == Approx(1.0));
  CHECK(cp.point_on_p.x() >= 1.0 - 1e-12);
  // Parallel, disjoint along the axis.
  cp = segment_closest_points({0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 1, 0});
  CHECK(cp.distance_m == Approx(std::sqrt(2.0)));
  // Both degenerate (points).
  cp = segment_closest_points({0, 0, 0}, {0, 0, 0}, {0, 3, 4}, {0, 3, 4});
  CHECK(cp.distance_m == Approx(5.0));
  // One degenerate.
  cp = segment_closest_points({0, 1, 0}, {0, 1, 0}, {-1, 0, 0}, {1, 0, 0});
  CHECK(cp.distance_m == Approx(1.0));
  CHECK(cp.t == Approx(0.5));
}

TEST_CASE("capsule contact depth and normal") {
  const Capsule a{{0, 0, 0}, {0, 1, 0}, 0.2};
  const Capsule b{{0.3, 0, 0}, {0.3, 1, 0}, 0.2};
  const auto c = capsule_contact(a, b);
  CHECK(c.depth_m == Approx(0.1));
  CHECK(c.normal.isApprox(Vec3(-1, 0, 0)));
  // Separating a along the normal by depth removes the overlap.
  const Capsule moved{a.a + c.normal * c.depth_m, a.b + c.normal * c.depth_m, a.radius_m};
  CHECK(capsule_contact(moved, b).depth_m == Approx(0.0).margin(1e-12));
}

TEST_CASE("capsule contact normal is defined when axes intersect") {
  const Capsule a{{-1, 0, 0}, {1, 0, 0}, 0.1};
  const Capsule b{{0, 0, -1}, {0, 0, 1}, 0.1};
  const auto c = capsule_contact(a, b);
  CHECK(c.depth_m == Approx(0.2));
  CHECK(std::abs(c.normal.norm() - 1.0) < 1e-12);
  CHECK(std::abs(c.normal.dot(Vec3::UnitX())) < 1e-12);
  CHECK(std::abs(c.normal.dot(Vec3::UnitZ())) < 1e-12);
  // Coincident parallel axes.
  const auto d = capsule_contact(a, a);
  CHECK(std::abs(d.normal.norm() - 1.0) < 1e-12);
  CHECK(std::abs(d.normal.dot(Vec3::UnitX())) < 1e-12);
}

TEST_CASE("capsule volume is cylinder plus sphere") {
  const Capsule c{{0, 0, 0}, {0, 2, 0}, 0.5};
  CHECK(c.volume_m3() == Approx(M_PI * 0.25 * 2 + 4.0 / 3.0 * M_PI * 0.125));
}

TEST_CASE("ttca/dtca on hand-built pairs (seed 001 Eqs. 2-3)") {
  // Head-on, 0.4 m lateral offset, closing at 2 m/s from 4 m apart: ttca 2 s, dtca 0.4 m.
  auto ca = closest_approach({0, 0}, {1, 0}, {4, 0.4}, {-1, 0});
  CHECK(ca.ttca_s == Approx(2.0));
  CHECK(ca.dtca_m == Approx(0.4));
  // Moving apart: negative ttca.
  ca = closest_approach({0, 0}, {-1, 0}, {4, 0.4}, {1, 0});
  CHECK(ca.ttca_s < 0.0);
  // Same velocity: infinite ttca, dtca is the current distance.
  ca = closest_approach({0, 0}, {1, 0}, {3, 4}, {1, 0});
  CHECK(std::isinf(ca.ttca_s));
  CHECK(ca.dtca_m == Approx(5.0));
}

}  // namespace test_geometry
