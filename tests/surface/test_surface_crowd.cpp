// Agents on surfaces: they stay on the mesh, cross creases and seams, and avoid exactly the agents
// they can reach (seed 002).
#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "framework/core/sha256.hpp"
#include "framework/surface/geodesic_distance.hpp"
#include "framework/surface/surface_measures.hpp"
#include "framework/surface/surface_scenes.hpp"
#include "framework/surface/triangle_bvh.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_surface_crowd {

using namespace crowdlab;

namespace {
SurfacePoint place(const SurfaceMesh& m, const Vec3& p) {
  // The face whose plane contains p and whose barycentric coordinates are all >= 0.
  for (int f = 0; f < m.face_count(); ++f)
    if (distance_to_face(m, f, p) < 1e-9) return SurfacePoint{f, p, 1.0};
  FAIL("point not on mesh");
  return {};
}

/// Two agents with hand-set goals walking toward each other's start.
struct Duel {
  SurfaceCrowdModel model;
  SurfaceCrowdState state;
};
Duel duel(std::shared_ptr<const SurfaceMesh> mesh, const Vec3& a, const Vec3& b, const Vec3& goal_a,
          const Vec3& goal_b, RelevantMode mode, SurfaceAvoidance avoidance) {
  SurfaceCrowdParams p;
  p.relevant = mode;
  p.avoidance = avoidance;
  Duel d{make_surface_crowd_model(mesh, p, 1, 1), {}};
  d.model.goal_vertices = {nearest_vertex(*mesh, goal_a), nearest_vertex(*mesh, goal_b)};
  d.model.goal_fields = {geodesic_distance_field(*mesh, {d.model.goal_vertices[0]}),
                         geodesic_distance_field(*mesh, {d.model.goal_vertices[1]})};
  d.state.points = {place(*mesh, a), place(*mesh, b)};
  d.state.velocity_mps = {Vec3::Zero(), Vec3::Zero()};
  d.state.goal = {0, 1};
  return d;
}
}  // namespace

TEST_CASE("an agent walking around the Mobius strip comes back upside down, never leaving the surface") {
  const SurfaceMesh m = make_mobius_strip(6, 1.5, 240, 8);
  SurfacePoint pt = place(m, Vec3(6, 0, 0));
  const Vec3 up0 = pt.up(m);
  // The centre line is not a geodesic, so steer along it like a goal-following agent: each step aims
  // along the circle's tangent at the current angle, projected onto the current triangle.
  const double circumference = 2 * M_PI * 6;
  const int steps = 2000;
  double worst_off_surface = 0;
  for (int k = 0; k < steps; ++k) {
    const double u = std::atan2(pt.position_m.z(), pt.position_m.x());
    Vec3 vel = to_tangent(m, pt.face, Vec3(-std::sin(u), 0, std::cos(u))).normalized();
    move_on_surface(m, pt, vel * (circumference / steps), vel);
    worst_off_surface = std::max(worst_off_surface, distance_to_face(m, pt.face, pt.position_m));
  }
  CHECK((pt.position_m - Vec3(6, 0, 0)).norm() < 0.3);
  CHECK(pt.up(m).dot(up0) < -0.9);  // orientation carried continuously: one lap flips "up"
  CHECK(worst_off_surface < 1e-5);
}

TEST_CASE("walking into a wall continues up the wall") {
  const SurfaceMesh m = make_floor_and_wall(4, 0.5);
  SurfacePoint pt = place(m, Vec3(1.0, 0, 2.1));
  Vec3 v(-1, 0, 0);
  move_on_surface(m, pt, Vec3(-2.0, 0, 0), v);
  CHECK(pt.position_m.x() == Approx(0.0).margin(1e-9));
  CHECK(pt.position_m.y() == Approx(1.0).margin(1e-9));
  CHECK(v.isApprox(Vec3(0, 1, 0)));
  CHECK(pt.up(m).isApprox(Vec3(1, 0, 0)));
}

TEST_CASE("agents on opposite sides of a floor never avoid each other (visibility Relevant)") {
  const SurfaceAvoidance avoidance = GENERATE(SurfaceAvoidance::kSocialForces, SurfaceAvoidance::kOrca);
  INFO("model " << surface_avoidance_name(avoidance));
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_ceiling_slab(10, 0.2, 0.25));
  // Top surface y = 2.7 (normal up), bottom y = 2.5 (normal down): walking the same line in opposite
  // directions. Starts and goals on grid vertices; b walks 0.25 m to the side so a repulsion would push a
  // sideways.
  const Vec3 a(-3, 2.7, 0), b(3, 2.5, 0.25), goal_a(4, 2.7, 0), goal_b(-4, 2.5, 0.25);
  Duel d = duel(mesh, a, b, goal_a, goal_b, RelevantMode::kVisibility, avoidance);
  Duel e = duel(mesh, a, b, goal_a, goal_b, RelevantMode::kEuclidean, avoidance);
  double max_lateral_ours = 0, max_lateral_euclid = 0;
  int euclid_neighbours_seen = 0;
  for (int k = 0; k < 150; ++k) {
    euclid_neighbours_seen += e.state.neighbor_count.empty() ? 0 : e.state.neighbor_count[0];
    step_surface_crowd(d.model, d.state);
    step_surface_crowd(e.model, e.state);
    CHECK(d.state.neighbor_count[0] == 0);
    CHECK(d.state.neighbor_count[1] == 0);
    max_lateral_ours = std::max(max_lateral_ours, std::abs(d.state.points[0].position_m.z()));
    max_lateral_euclid = std::max(max_lateral_euclid, std::abs(e.state.points[0].position_m.z()));
  }
  INFO("lateral deviation: ours " << max_lateral_ours << " m, Euclidean " << max_lateral_euclid << " m");
  CHECK(max_lateral_ours < 0.01);     // walks straight past the agent on the other side of the floor
  CHECK(euclid_neighbours_seen > 0);  // the Euclidean baseline considers it (a false positive)...
  CHECK(max_lateral_euclid > max_lateral_ours + 0.05);  // ...and swerves for an agent it cannot reach
}

TEST_CASE("agents on perpendicular surfaces avoid each other through the stacked spheres") {
  const SurfaceAvoidance avoidance = GENERATE(SurfaceAvoidance::kSocialForces, SurfaceAvoidance::kOrca);
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_and_wall(8, 0.25));
  // One on the floor walking along the foot of the wall, one on the wall walking along its base the other
  // way: their feet are 1 m apart but their heads would meet.
  const Vec3 a(0.9, 0, 1.0), b(0, 0.9, 7.0);
  {
    // Without avoidance their straight paths collide head-on: at the passing point a's middle sphere
    // and b's middle sphere coincide. With a single sphere at the feet they would never interact.
    const StackedBody body;
    CHECK(stacked_clearance(Vec3(0.9, 0, 4), Vec3::UnitY(), Vec3(0, 0.9, 4), Vec3::UnitX(), body) < -0.4);
    CHECK((Vec3(0.9, 0, 4) + Vec3::UnitY() * body.sphere_radius_m - Vec3(0, 0.9, 4) -
           Vec3::UnitX() * body.sphere_radius_m)
              .norm() > 2 * body.sphere_radius_m);
  }
  for (RelevantMode mode : {RelevantMode::kVisibility, RelevantMode::kSurface}) {
    Duel d = duel(mesh, a, b, Vec3(0.9, 0, 7.5), Vec3(0, 0.9, 0.5), mode, avoidance);
    double min_clearance = 1e9;
    for (int k = 0; k < 200; ++k) {
      step_surface_crowd(d.model, d.state);
      const auto& p = d.state.points;
      min_clearance =
          std::min(min_clearance, stacked_clearance(p[0].position_m, body_up(d.model, p[0]), p[1].position_m,
                                                    body_up(d.model, p[1]), d.model.params.body));
    }
    INFO("model " << surface_avoidance_name(avoidance) << " relevant " << static_cast<int>(mode)
                  << " min clearance " << min_clearance);
    if (mode == RelevantMode::kVisibility) CHECK(min_clearance > -0.02);
  }
}

TEST_CASE("a crowd on the blob stays on the surface and is deterministic across thread counts") {
  const SurfaceAvoidance avoidance = GENERATE(SurfaceAvoidance::kSocialForces, SurfaceAvoidance::kOrca);
  INFO("model " << surface_avoidance_name(avoidance));
  auto mesh = std::make_shared<const SurfaceMesh>(make_blobby_surface(test::kSanitized ? 3000 : 20000, 6));
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    SurfaceCrowdParams params;
    params.avoidance = avoidance;
    SurfaceCrowdModel model = make_surface_crowd_model(mesh, params, 4, 99);
    SurfaceCrowdState s = spawn_surface_agents(model, 150, 99);
    TriangleBvh bvh(*mesh);
    SurfaceCrowdMeasures m;
    for (int k = 0; k < (test::kSanitized ? 20 : 90); ++k) {
      step_surface_crowd(model, s);
      accumulate_surface_measures(model, s, bvh, m);
    }
    std::string bytes;
    for (const auto& p : s.points)
      bytes.append(reinterpret_cast<const char*>(p.position_m.data()), sizeof(double) * 3);
    return std::make_pair(sha256_hex(bytes), m);
  };
  const auto [h1, m1] = run(1);
  const auto [h2, m2] = run(2);
  const auto [h3, m3] = run(1);
  CHECK(h1 == h2);
  CHECK(h1 == h3);  // same seed, same result
  CHECK(m1.max_distance_to_surface_m < 1e-5);
  INFO("collision % " << m1.collision_percent());
  CHECK(m1.collision_percent() < 5.0);
}

TEST_CASE("agent height, sphere radius and spacing are parameters of the stacked body") {
  StackedBody body;
  CHECK(body.sphere_center(Vec3::Zero(), Vec3::UnitY(), 2).y() == Approx(1.8 - 0.25));  // spans feet to head
  body.sphere_spacing_m = 0.3;
  body.sphere_radius_m = 0.2;
  for (int i = 0; i < 3; ++i)
    CHECK((body.sphere_center(Vec3(1, 2, 3), Vec3::UnitX(), i) - Vec3(1.2 + 0.3 * i, 2, 3)).norm() < 1e-12);
  // Two agents side by side on a floor, 0.45 m apart: the radius decides whether they overlap.
  CHECK(stacked_clearance(Vec3::Zero(), Vec3::UnitY(), Vec3(0.45, 0, 0), Vec3::UnitY(), body) ==
        Approx(0.05));
  SurfaceCrowdParams p;
  p.body.sphere_spacing_m = -1;
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_and_wall(4, 0.5));
  CHECK_THROWS_AS(make_surface_crowd_model(mesh, p, 1, 1), InputError);
}

TEST_CASE("a body crossing a crease tilts over several steps instead of snapping by the crease angle") {
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_and_wall(4, 0.5));
  for (bool smooth : {true, false}) {
    SurfaceCrowdParams p;
    p.smooth_body_up = smooth;
    const SurfaceCrowdModel model = make_surface_crowd_model(mesh, p, 1, 1);
    SurfacePoint pt = place(*mesh, Vec3(1.5, 0, 2.1));
    Vec3 v(-1.3, 0, 0);
    double worst_turn_deg = 0, worst_centre_jump_m = 0;
    Vec3 up = body_up(model, pt), centre = body_center(model, pt);
    for (int k = 0; k < 90; ++k) {  // 3 s at 1.3 m/s, 30 Hz: from the floor 2.4 m up the wall
      move_on_surface(*mesh, pt, v * p.dt_s, v);
      const Vec3 next_up = body_up(model, pt), next_centre = body_center(model, pt);
      worst_turn_deg =
          std::max(worst_turn_deg, std::acos(std::clamp(up.dot(next_up), -1.0, 1.0)) * 180 / M_PI);
      worst_centre_jump_m = std::max(worst_centre_jump_m, (next_centre - centre).norm());
      up = next_up;
      centre = next_centre;
    }
    INFO("smooth " << smooth << ": worst turn " << worst_turn_deg << " deg, worst centre jump "
                   << worst_centre_jump_m << " m per step");
    CHECK(up.isApprox(Vec3::UnitX()));  // standing on the wall at the end either way
    if (smooth) {
      // The 90 degree turn spreads over the two 0.5 m triangles at the crease: ~1 m of walking, ~23
      // steps, about 4 degrees each; the body centre moves little more than the feet (4.3 cm).
      CHECK(worst_turn_deg < 10);
      CHECK(worst_centre_jump_m < 0.15);
    } else {
      CHECK(worst_turn_deg > 89);  // the face normal snaps: the head sweeps 1.3 m in one step
      CHECK(worst_centre_jump_m > 1.0);
    }
  }
}

TEST_CASE(
    "neighbours are ranked by body clearance: a head-on-head agent on the wall beats ten on the floor") {
  auto mesh = std::make_shared<const SurfaceMesh>(make_floor_and_wall(10, 0.5));
  SurfaceCrowdParams p;
  p.relevant = RelevantMode::kEuclidean;
  p.max_neighbors = 10;
  SurfaceCrowdModel model = make_surface_crowd_model(mesh, p, 1, 1);
  SurfaceCrowdState s;
  // a on the floor 1.9 m from the wall; w on the wall 1.83 m up: their heads touch (clearance < 0)
  // although their centres are 1.38 m apart. Ten floor agents on the far side of a, with centres 0.95 to
  // 1.3 m from a's, have larger clearances (0.45 to 0.8 m) but nearer centres.
  s.points.push_back(place(*mesh, Vec3(1.9, 0, 5)));
  s.points.push_back(place(*mesh, Vec3(0, 1.83, 5.2)));
  for (int k = 0; k < 10; ++k) {
    const double angle = -1.2 + 2.4 * k / 9.0, r = 0.95 + 0.35 * k / 9.0;
    s.points.push_back(place(*mesh, Vec3(1.9 + r * std::cos(angle), 0, 5 + r * std::sin(angle))));
  }
  const size_t n = s.points.size();
  s.velocity_mps.assign(n, Vec3::Zero());
  s.goal.assign(n, 0);
  const Vec3 up_a = body_up(model, s.points[0]), up_w = body_up(model, s.points[1]);
  REQUIRE(stacked_clearance(s.points[0].position_m, up_a, s.points[1].position_m, up_w, p.body) < 0);
  for (size_t k = 2; k < n; ++k) {
    REQUIRE((body_center(model, s.points[k]) - body_center(model, s.points[0])).norm() <
            (body_center(model, s.points[1]) - body_center(model, s.points[0])).norm());
    REQUIRE(stacked_clearance(s.points[0].position_m, up_a, s.points[k].position_m,
                              body_up(model, s.points[k]), p.body) > 0.3);
  }
  step_surface_crowd(model, s);
  REQUIRE(s.neighbor_count[0] == 10);
  const auto first = s.neighbors.begin();
  CHECK(std::find(first, first + 10, 1) != first + 10);
}

TEST_CASE("the mesh-near-feet visibility sees over a thin slab's edge where the 1 m disk hides") {
  const SurfaceMesh slab = make_floor_ceiling_slab(10, 0.2, 0.5);  // top y = 2.7, sides x = +-5
  const TriangleBvh bvh(slab);
  const StackedBody body;
  // a on the top 10 cm from the edge, b on the 20 cm side face: the segment to b's head leaves the
  // slab above its top, where the disk at b's feet claims surface that is not there.
  const Vec3 feet_a(-4.9, 2.7, 0), up_a = Vec3::UnitY(), feet_b(-5.0, 2.6, 0.3), up_b = -Vec3::UnitX();
  CHECK_FALSE(mutually_visible(feet_a, up_a, feet_b, up_b, body));           // disk: a false negative
  CHECK(mutually_visible_near_feet(feet_a, up_a, feet_b, up_b, body, bvh));  // mesh: visible
  CHECK(stacked_clearance(feet_a, up_a, feet_b, up_b, body) < 0.5);          // and they can touch
  // Through the slab (one on top, one below): both tests hide the agent.
  const Vec3 feet_c(-1.0, 2.5, 0.4), up_c = -Vec3::UnitY();
  CHECK_FALSE(mutually_visible(Vec3(-1, 2.7, 0), up_a, feet_c, up_c, body));
  CHECK_FALSE(mutually_visible_near_feet(Vec3(-1, 2.7, 0), up_a, feet_c, up_c, body, bvh));
  // Property over random pairs on the two-storey building: "hidden near the feet" implies the full
  // segment hits the mesh (the test inspects a part of it).
  const SurfaceMesh building = make_two_storey_building();
  const TriangleBvh bvh_b(building);
  Rng rng(7);
  int hidden = 0;
  for (int k = 0; k < (test::kSanitized ? 300 : 3000); ++k) {
    const int fa = static_cast<int>(uniform_index(rng, static_cast<size_t>(building.face_count())));
    const int fb = static_cast<int>(uniform_index(rng, static_cast<size_t>(building.face_count())));
    const Vec3 pa = building.centroid(fa), pb = building.centroid(fb);
    const Vec3 ua = building.face_normals[static_cast<size_t>(fa)],
               ub = building.face_normals[static_cast<size_t>(fb)];
    if ((pa - pb).norm() > 4) continue;
    if (!mutually_visible_near_feet(pa, ua, pb, ub, body, bvh_b)) {
      ++hidden;
      CHECK(bvh_b.segment_hits(pa + ua * kEyeLift, pb + ub * body.height_m));
    }
  }
  CHECK(hidden > 0);
}

}  // namespace test_surface_crowd
