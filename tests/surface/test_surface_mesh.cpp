// Surface meshes: connectivity, orientation, repairs, errors, and the shipped scenes.
#include <catch2/catch.hpp>
#include <fstream>
#include <set>

#include "framework/core/error.hpp"
#include "framework/surface/geodesic_distance.hpp"
#include "framework/surface/surface_scenes.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_surface_mesh {

using namespace crowdlab;

namespace {
int boundary_edges(const SurfaceMesh& m) {
  int n = 0;
  for (const auto& nb : m.neighbors)
    for (int f : nb) n += f < 0;
  return n;
}
int euler_characteristic(const SurfaceMesh& m) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : m.triangles)
    for (int e = 0; e < 3; ++e)
      edges.insert({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])});
  return static_cast<int>(m.vertices_m.size()) - static_cast<int>(edges.size()) + m.face_count();
}
int flipped_edges(const SurfaceMesh& m) {
  int n = 0;
  for (const auto& fl : m.flips_orientation)
    for (bool b : fl) n += b;
  return n;
}
}  // namespace

TEST_CASE("closed scenes are watertight with the right topology") {
  const SurfaceMesh torus = make_torus(6, 2, 40, 16);
  CHECK(boundary_edges(torus) == 0);
  CHECK(euler_characteristic(torus) == 0);
  CHECK(flipped_edges(torus) == 0);
  const SurfaceMesh blob = make_blobby_surface(2000, 5);
  CHECK(boundary_edges(blob) == 0);
  CHECK(euler_characteristic(blob) == 2);
  CHECK(flipped_edges(blob) == 0);
  const SurfaceMesh slab = make_floor_ceiling_slab(4, 0.2, 0.5);
  CHECK(boundary_edges(slab) == 0);
  CHECK(euler_characteristic(slab) == 2);
  CHECK(flipped_edges(slab) == 0);
  // Torus area 4 pi^2 R r (polygonal approximation slightly smaller).
  CHECK(torus.total_area_m2 == Approx(4 * M_PI * M_PI * 12).epsilon(0.02));
}

TEST_CASE("the Mobius strip is one-sided: exactly one seam of orientation-reversing edges") {
  const SurfaceMesh m = make_mobius_strip(6, 1.5, 120, 6);
  CHECK(flipped_edges(m) == 2 * 6 * 2 / 2 * 1);  // 6 seam edges, seen from both sides
  CHECK(euler_characteristic(m) == 0);
}

TEST_CASE("open scenes: floor-wall and the building are manifold and consistently oriented") {
  for (const SurfaceMesh& m :
       {make_floor_and_wall(4, 0.5), make_two_storey_building(2.6, 0.5), make_tree()}) {
    INFO(m.name);
    CHECK(flipped_edges(m) == 0);
    CHECK(m.face_count() > 0);
  }
  // The building's floor normals point up, and its second storey lies above the first.
  const SurfaceMesh b = make_two_storey_building(2.6, 0.5);
  double max_y = 0;
  for (size_t f = 0; f < b.face_normals.size(); ++f) CHECK(b.face_normals[f].y() > 0.9);
  for (const Vec3& v : b.vertices_m) max_y = std::max(max_y, v.y());
  CHECK(max_y == Approx(5.2));
}

TEST_CASE("the high-resolution blob has at least 100k triangles") {
  if (test::kSanitized) return;
  CHECK(make_blobby_surface().face_count() >= 100000);
}

TEST_CASE("bad meshes are rejected with a clear message") {
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0, -1, 0}};
  // Three triangles sharing edge (0,1): non-manifold.
  CHECK_THROWS_WITH(make_surface_mesh(v, {{0, 1, 2}, {0, 1, 3}, {0, 1, 4}}, "t"),
                    Catch::Contains("non-manifold"));
  CHECK_THROWS_WITH(make_surface_mesh(v, {{0, 1, 9}}, "t"), Catch::Contains("out of range"));
  CHECK_THROWS_AS(make_surface_mesh({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, {{0, 1, 2}}, "t"),
                  InputError);  // degenerate
  std::vector<Vec3> nan = v;
  nan[1].x() = std::nan("");
  CHECK_THROWS_WITH(make_surface_mesh(nan, {{0, 1, 2}}, "t"), Catch::Contains("not finite"));
  const auto dir = test::scratch_dir("surface_obj");
  { std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 x\n"; }
  CHECK_THROWS_WITH(load_obj_surface((dir / "bad.obj").string()), Catch::Contains("bad.obj:4"));
  { std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1/1/1 2/2/2 3/3/3 4/4/4\n"; }
  CHECK(load_obj_surface((dir / "quad.obj").string()).face_count() == 2);
  CHECK_THROWS_AS(make_surface_scene("no-such-scene"), InputError);
}

TEST_CASE("geodesic distance on a flat floor matches Euclidean distance") {
  const SurfaceMesh floor = make_floor_and_wall(10, 0.25);
  const int source = nearest_vertex(floor, Vec3(5, 0, 5));
  const auto d = geodesic_distance_field(floor, {source});
  double worst = 0;
  for (size_t i = 0; i < floor.vertices_m.size(); ++i) {
    const Vec3& p = floor.vertices_m[i];
    if (p.y() > 1e-9) continue;  // floor only
    const double exact = (p - Vec3(5, 0, 5)).norm();
    if (exact > 1.0) worst = std::max(worst, std::abs(d[i] - exact) / exact);
  }
  INFO("worst relative error " << worst);
  CHECK(worst < 0.02);  // edge-only Dijkstra would be ~8 % off on diagonals
  // Up the wall: the path goes over the crease, so distance = distance to the crease + height.
  const int on_wall = nearest_vertex(floor, Vec3(0, 3, 5));
  CHECK(d[static_cast<size_t>(on_wall)] == Approx(8.0).epsilon(0.02));
}

}  // namespace test_surface_mesh
