// Overlap volume against analytic cases: sphere-sphere lens, parallel and coaxial capsules,
// perpendicular (offset) cylinders, plus symmetry, separation, monotonicity and the error bound.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "framework/metrics/lens_volume.hpp"
#include "framework/metrics/overlap_volume.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_overlap_volume {

using namespace crowdlab;

namespace {

Vec3 random_unit(Rng& rng) {
  for (;;) {
    const Vec3 v(2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1, 2 * uniform01(rng) - 1);
    if (v.norm() > 0.1 && v.norm() < 1.0) return v.normalized();
  }
}

double rand_in(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * uniform01(rng);
}

/// Checks estimate within 1 % of exact, and the rigorous bracket contains the exact value.
void check_against(const OverlapVolume& v, double exact) {
  INFO("estimate " << v.volume_m3 << " exact " << exact << " bracket [" << v.lower_m3 << ", " << v.upper_m3
                   << "] evaluations " << v.chord_evaluations);
  CHECK(std::abs(v.volume_m3 - exact) <= 0.01 * exact);
  CHECK(v.lower_m3 <= exact * (1 + 1e-9));
  CHECK(v.upper_m3 >= exact * (1 - 1e-9));
  CHECK(std::abs(v.volume_m3 - exact) <= v.error_bound_m3() + 1e-15);
}

int cases() {
  return test::kSanitized ? 10 : 60;
}

}  // namespace

TEST_CASE("lens_volume matches limiting cases and a numeric integral") {
  const double pi = std::numbers::pi;
  CHECK(lens_volume(0.1, 0.2, 0.31) == 0.0);
  CHECK(lens_volume(0.1, 0.2, 0.05) == Approx(4.0 / 3.0 * pi * 1e-3));
  // Equal spheres: V = pi (4r + d)(2r - d)^2 / 12.
  CHECK(lens_volume(0.1, 0.1, 0.12) == Approx(pi * (0.4 + 0.12) * 0.08 * 0.08 / 12.0));
  // Continuity at internal tangency.
  CHECK(lens_volume(0.1, 0.2, 0.1 + 1e-9) == Approx(4.0 / 3.0 * pi * 1e-3).epsilon(1e-6));
  // Numeric slab integration for unequal spheres.
  const double r1 = 0.13, r2 = 0.08, d = 0.15;
  double numeric = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = -r1 + (i + 0.5) * (2 * r1) / n;  // along the centre line; sphere 1 at 0, sphere 2 at d
    const double a1 = r1 * r1 - x * x, a2 = r2 * r2 - (x - d) * (x - d);
    if (a1 > 0 && a2 > 0) numeric += pi * std::min(a1, a2) * (2 * r1) / n;
  }
  CHECK(lens_volume(r1, r2, d) == Approx(numeric).epsilon(1e-5));
  CHECK(circle_lens_area(0.1, 0.1, 0.0) == Approx(pi * 0.01));
  CHECK(circle_lens_area(0.1, 0.1, 0.2) == 0.0);
  CHECK_THROWS_AS(lens_volume(-1.0, 0.1, 0.1), InputError);
}

TEST_CASE("sphere-sphere overlap is within 1 % of the lens volume and inside its bound") {
  Rng rng(derive_seed(7, "lens"));
  for (int c = 0; c < cases(); ++c) {
    const double r1 = rand_in(rng, 0.03, 0.2), r2 = rand_in(rng, 0.03, 0.2);
    const double lo = std::abs(r1 - r2), hi = r1 + r2;
    const double d = lo + (hi - lo) * rand_in(rng, 0.05, 0.97);  // at least a 3 % lens depth
    const Vec3 p = Vec3(rand_in(rng, -5, 5), rand_in(rng, 0, 2), rand_in(rng, -5, 5));
    const Vec3 q = p + d * random_unit(rng);
    const std::vector<Capsule> a = {{p, p, r1}}, b = {{q, q, r2}};
    check_against(overlap_volume(a, b), lens_volume(r1, r2, d));
  }
}

TEST_CASE("parallel capsules: disc-lens area x length + one sphere lens for the two half-caps") {
  Rng rng(derive_seed(7, "parallel"));
  for (int c = 0; c < cases(); ++c) {
    const double r1 = rand_in(rng, 0.04, 0.15), r2 = rand_in(rng, 0.04, 0.15);
    const double lo = std::abs(r1 - r2), hi = r1 + r2;
    const double d = lo + (hi - lo) * rand_in(rng, 0.05, 0.95);
    const double length = rand_in(rng, 0.05, 0.6);
    const Vec3 u = random_unit(rng);
    const Vec3 n = any_perpendicular(u);
    const Vec3 p(rand_in(rng, -1, 1), rand_in(rng, 0, 2), rand_in(rng, -1, 1));
    const std::vector<Capsule> a = {{p, p + length * u, r1}};
    const std::vector<Capsule> b = {{p + d * n, p + d * n + length * u, r2}};
    // Beyond each end plane both capsules are hemispheres centred on that plane: half a lens each.
    const double exact = circle_lens_area(r1, r2, d) * length + lens_volume(r1, r2, d);
    check_against(overlap_volume(a, b), exact);
  }
}

TEST_CASE("coaxial capsules overlap in a capsule (or a lens when only the caps meet)") {
  Rng rng(derive_seed(7, "coaxial"));
  const double pi = std::numbers::pi;
  for (int c = 0; c < cases(); ++c) {
    const double r = rand_in(rng, 0.04, 0.15);
    const double l1 = rand_in(rng, 0.1, 0.5), l2 = rand_in(rng, 0.1, 0.5);
    const double start = rand_in(rng, 0.02, l1 + 1.9 * r);  // B starts here along A's axis
    const Vec3 u = random_unit(rng);
    const Vec3 p(rand_in(rng, -1, 1), rand_in(rng, 0, 2), rand_in(rng, -1, 1));
    const std::vector<Capsule> a = {{p, p + l1 * u, r}};
    const std::vector<Capsule> b = {{p + start * u, p + (start + l2) * u, r}};
    const double shared = std::min(l1, start + l2) - start;
    const double exact = shared >= 0 ? pi * r * r * (shared + 4.0 / 3.0 * r) : lens_volume(r, r, -shared);
    check_against(overlap_volume(a, b), exact);
  }
}

TEST_CASE("perpendicular capsules: offset bicylinder against a 1D integral of rectangle areas") {
  // A along x (radius r1), B along z (radius r2) offset by d in y, both long enough that only their
  // cylinders meet: the section at height y is a rectangle 2 sqrt(r1^2 - y^2) x 2 sqrt(r2^2 - (y-d)^2).
  Rng rng(derive_seed(7, "perpendicular"));
  for (int c = 0; c < (test::kSanitized ? 5 : 20); ++c) {
    const double r1 = rand_in(rng, 0.04, 0.15), r2 = rand_in(rng, 0.04, 0.15);
    const double d = rand_in(rng, 0.0, 0.9) * (r1 + r2);
    const double ylo = std::max(-r1, d - r2), yhi = std::min(r1, d + r2);
    // Substitution y = m + w sin(phi) removes the square-root endpoint singularities.
    const double m = 0.5 * (ylo + yhi), w = 0.5 * (yhi - ylo);
    double exact = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double phi = -std::numbers::pi / 2 + (i + 0.5) * std::numbers::pi / n;
      const double y = m + w * std::sin(phi);
      const double area = 4 * std::sqrt(std::max(0.0, r1 * r1 - y * y)) *
                          std::sqrt(std::max(0.0, r2 * r2 - (y - d) * (y - d)));
      exact += area * w * std::cos(phi) * std::numbers::pi / n;
    }
    const std::vector<Capsule> a = {{Vec3(-0.5, 1, 0), Vec3(0.5, 1, 0), r1}};
    const std::vector<Capsule> b = {{Vec3(0, 1 + d, -0.5), Vec3(0, 1 + d, 0.5), r2}};
    if (d == 0.0 && r1 == r2) CHECK(exact == Approx(16.0 / 3.0 * r1 * r1 * r1).epsilon(1e-6));
    check_against(overlap_volume(a, b), exact);
  }
}

TEST_CASE("overlap is symmetric, zero when apart and counts a body's own overlaps once") {
  Rng rng(derive_seed(7, "props"));
  for (int c = 0; c < cases(); ++c) {
    std::vector<Capsule> a, b;
    for (int i = 0; i < 4; ++i) {
      const Vec3 p(rand_in(rng, -0.2, 0.2), rand_in(rng, 0.8, 1.2), rand_in(rng, -0.2, 0.2));
      a.push_back({p, p + rand_in(rng, 0.0, 0.4) * random_unit(rng), rand_in(rng, 0.04, 0.12)});
      const Vec3 q(rand_in(rng, -0.2, 0.2) + 0.15, rand_in(rng, 0.8, 1.2), rand_in(rng, -0.2, 0.2));
      b.push_back({q, q + rand_in(rng, 0.0, 0.4) * random_unit(rng), rand_in(rng, 0.04, 0.12)});
    }
    const OverlapVolume ab = overlap_volume(a, b), ba = overlap_volume(b, a);
    CHECK(ab.volume_m3 == Approx(ba.volume_m3).epsilon(0.01).margin(1e-7));
    // Duplicating A's capsules changes nothing (union semantics).
    std::vector<Capsule> a2 = a;
    a2.insert(a2.end(), a.begin(), a.end());
    CHECK(overlap_volume(a2, b).volume_m3 == Approx(ab.volume_m3).epsilon(1e-9).margin(1e-12));
    // Moved far apart: exactly zero.
    std::vector<Capsule> far = b;
    for (Capsule& cap : far) {
      cap.a.x() += 3.0;
      cap.b.x() += 3.0;
    }
    const OverlapVolume zero = overlap_volume(a, far);
    CHECK(zero.volume_m3 == 0.0);
    CHECK(zero.upper_m3 == 0.0);
    CHECK_FALSE(zero.colliding);
  }
  // Just touching (distance == r1 + r2 + epsilon) is zero.
  const std::vector<Capsule> s1 = {{Vec3::Zero(), Vec3::Zero(), 0.1}},
                             s2 = {{Vec3(0.2000001, 0, 0), Vec3(0.2000001, 0, 0), 0.1}};
  CHECK(overlap_volume(s1, s2).volume_m3 == 0.0);
}

TEST_CASE("overlap grows monotonically with penetration depth") {
  const std::vector<Capsule> arm = {{Vec3(-0.3, 1.2, 0), Vec3(0.3, 1.2, 0), 0.05},
                                    {Vec3(0, 0.9, 0), Vec3(0, 1.5, 0), 0.12}};
  double previous = 0.0;
  for (int step = 1; step <= 20; ++step) {
    const double gap = 0.33 - 0.015 * step;  // second body's axis distance from the first's centre
    const std::vector<Capsule> other = {{Vec3(gap, 0.8, 0.05), Vec3(gap, 1.6, 0.05), 0.1}};
    const double v = overlap_volume(arm, other).volume_m3;
    INFO("step " << step << " gap " << gap << " volume " << v);
    CHECK(v >= previous);
    previous = v;
  }
  CHECK(previous > 0.0);
}

TEST_CASE("overlap_volume rejects bad capsules") {
  const std::vector<Capsule> ok = {{Vec3::Zero(), Vec3::UnitX(), 0.1}};
  const std::vector<Capsule> nan = {{Vec3(std::nan(""), 0, 0), Vec3::UnitX(), 0.1}};
  const std::vector<Capsule> zero_r = {{Vec3::Zero(), Vec3::UnitX(), 0.0}};
  CHECK_THROWS_AS(overlap_volume(ok, nan), InputError);
  CHECK_THROWS_AS(overlap_volume(zero_r, ok), InputError);
}

}  // namespace test_overlap_volume
