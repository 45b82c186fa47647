// Properties of core/aabb.hpp and core/capsule_box.hpp: the box of a capsule holds every point of the
// capsule and is tight on every axis; overlap, containment and distance agree with point sampling.
#include <catch2/catch.hpp>
#include <random>

#include "framework/core/capsule_box.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_aabb {

using namespace crowdlab;

namespace {
Vec3 random_vec(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}
}  // namespace

TEST_CASE("capsule_box holds the capsule and is tight on every axis") {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Capsule c{random_vec(rng, 1.0), random_vec(rng, 1.0),
                    0.05 + 0.1 * std::abs(random_vec(rng, 1.0).x())};
    const Aabb box = capsule_box(c);
    // The extreme point of a capsule along +-axis k is an endpoint moved by the radius along that axis.
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = Vec3::Unit(k);
      const double top = std::max(c.a[k], c.b[k]) + c.radius_m,
                   bottom = std::min(c.a[k], c.b[k]) - c.radius_m;
      CHECK(box.hi[k] == Approx(top).margin(1e-15));
      CHECK(box.lo[k] == Approx(bottom).margin(1e-15));
      CHECK(box.contains((c.a[k] > c.b[k] ? c.a : c.b) + c.radius_m * e));
    }
    const Aabb grown = capsule_box(c, 0.25);
    CHECK((grown.hi - box.hi).isApprox(Vec3::Constant(0.25)));
    CHECK((box.lo - grown.lo).isApprox(Vec3::Constant(0.25)));
  }
}

TEST_CASE("capsules_box is the union of the capsule boxes, the empty set gives an empty box") {
  const std::array<Capsule, 2> caps{Capsule{{0, 0, 0}, {1, 0, 0}, 0.1}, Capsule{{0, 2, 0}, {0, 3, -1}, 0.2}};
  const Aabb box = capsules_box(caps);
  CHECK(box.lo.isApprox(Vec3(-0.2, -0.1, -1.2)));
  CHECK(box.hi.isApprox(Vec3(1.1, 3.2, 0.2)));
  const Aabb none = capsules_box(std::span<const Capsule>{});
  CHECK_FALSE(none.contains(Vec3::Zero()));
  CHECK_FALSE(none.overlaps(box));
}

TEST_CASE("Aabb overlap, intersection and squared distance") {
  const Aabb a{{0, 0, 0}, {1, 1, 1}}, b{{1, 0.5, 0.5}, {2, 2, 2}}, c{{1.5, 0, 0}, {2, 1, 1}};
  CHECK(a.overlaps(b));  // a shared face counts
  CHECK_FALSE(a.overlaps(c));
  const Aabb ab = a.intersection(b);
  CHECK(ab.lo.isApprox(Vec3(1, 0.5, 0.5)));
  CHECK(ab.hi.isApprox(Vec3(1, 1, 1)));
  CHECK(a.squared_distance({0.5, 0.5, 0.5}) == 0.0);
  CHECK(a.squared_distance({3, 1, -2}) == Approx(4.0 + 4.0));
  Aabb grown = a;
  grown.extend(c);
  CHECK(grown.contains({1.8, 0.2, 0.2}));
}

}  // namespace test_aabb
