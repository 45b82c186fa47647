// The capsule tessellation shown in viewers: on the surface, closed, outward-facing.
#include <catch2/catch.hpp>
#include <map>
#include <numbers>

#include "framework/core/seed.hpp"
#include "framework/io/capsule_mesh.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_capsule_mesh {

using namespace crowdlab;

namespace {

// Signed volume of a closed triangle mesh by the divergence theorem (positive when outward-facing).
double signed_volume(const TriangleSoup& s) {
  double v = 0.0;
  for (size_t t = 0; t < s.indices.size(); t += 3)
    v += s.positions[s.indices[t]].dot(s.positions[s.indices[t + 1]].cross(s.positions[s.indices[t + 2]])) /
         6.0;
  return v;
}

}  // namespace

TEST_CASE("capsule meshes lie on the capsule, are closed 2-manifolds and face outward") {
  Rng rng(3);
  for (int trial = 0; trial < 40; ++trial) {
    Capsule c;
    c.a = Vec3(uniform01(rng), uniform01(rng), uniform01(rng));
    c.b = trial % 5 == 0
              ? c.a
              : Vec3(c.a + Vec3(standard_normal(rng), standard_normal(rng), standard_normal(rng)) * 0.3);
    c.radius_m = 0.02 + 0.1 * uniform01(rng);
    const int segments = 3 + trial % 10, rings = 1 + trial % 4;
    TriangleSoup s;
    append_capsule_mesh(c, segments, rings, s);
    INFO("trial " << trial << " segments " << segments << " rings " << rings);
    const bool sphere = c.length_m() == 0.0;
    CHECK(s.positions.size() == static_cast<size_t>(2 + segments * (sphere ? 2 * rings - 1 : 2 * rings)));
    for (size_t i = 0; i < s.positions.size(); ++i) {
      const auto cp = segment_closest_points(c.a, c.b, s.positions[i], s.positions[i]);
      CHECK(cp.distance_m == Approx(c.radius_m).margin(1e-12));
      CHECK(s.normals[i].norm() == Approx(1.0).margin(1e-12));
    }
    // Closed: every undirected edge is used by exactly two triangles, once in each direction.
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (size_t t = 0; t < s.indices.size(); t += 3)
      for (int k = 0; k < 3; ++k)
        ++directed[{s.indices[t + static_cast<size_t>(k)], s.indices[t + static_cast<size_t>((k + 1) % 3)]}];
    bool manifold = true;
    for (const auto& [edge, count] : directed)
      manifold = manifold && count == 1 && directed.count({edge.second, edge.first}) == 1;
    CHECK(manifold);
    // Euler characteristic of a sphere: V - E + F = 2.
    const long faces = static_cast<long>(s.indices.size() / 3);
    CHECK(static_cast<long>(s.positions.size()) - static_cast<long>(directed.size() / 2) + faces == 2);
    // Inscribed polyhedron: positive (outward) volume below the capsule's.
    const double v = signed_volume(s);
    CHECK(v > 0.0);
    CHECK(v < c.volume_m3());
  }
  // Finer tessellations converge to the exact capsule volume.
  const Capsule c{Vec3::Zero(), Vec3(0, 0.4, 0), 0.1};
  TriangleSoup fine;
  append_capsule_mesh(c, 256, 64, fine);
  CHECK(signed_volume(fine) == Approx(c.volume_m3()).epsilon(1e-3));
}

}  // namespace test_capsule_mesh
