// The `manifold` scenario end to end in the library: surface trajectories -> developed 2D walk ->
// full-body animation -> bodies stood on the surface (orient_to_surface), on floors, walls and ceilings.
#include <catch2/catch.hpp>

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/orient_to_surface.hpp"
#include "framework/core/body_shape.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/surface/develop_surface_trajectories.hpp"
#include "framework/surface/generate_manifold_scenario.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_manifold_scenario {

using namespace crowdlab;

namespace {

ExperimentSpec manifold_spec(const std::string& mesh, CrowdModel model, int agents, double duration_s) {
  ExperimentSpec spec;
  spec.scenario.type = ScenarioKind::manifold;
  spec.scenario.mesh = mesh;
  spec.scenario.agents = agents;
  spec.crowd.model = model;
  spec.crowd.neighbor_distance_m = 3.0;
  spec.duration_s = duration_s;
  spec.fps = 15;
  return spec;
}

Condition condition(std::uint64_t seed) {
  Condition c;
  c.id = "manifold-test";
  c.seed = seed;
  return c;
}

}  // namespace

TEST_CASE("developing a surface walk keeps step lengths and turning, and ignores creases") {
  // A walk along +X on the floor, over the crease at x = 0 up the wall x = 0... expressed directly:
  // 10 frames on the floor heading -X, then 10 frames on the wall heading +Y, then a 90 degree left turn.
  SurfaceTrajectories s;
  s.agents.resize(1);
  auto& a = s.agents[0];
  for (int f = 0; f < 10; ++f) {
    a.feet_m.emplace_back(1.0 - 0.1 * f, 0, 0);
    a.up.push_back(Vec3::UnitY());
    a.forward.push_back(-Vec3::UnitX());
  }
  for (int f = 0; f < 10; ++f) {
    a.feet_m.emplace_back(0, 0.1 * f, 0);  // frame 10 is on the crease
    a.up.push_back(Vec3::UnitX());
    a.forward.push_back(Vec3::UnitY());
  }
  const CrowdTrajectories d = develop_surface_trajectories(s, 10, 0.25);
  REQUIRE(d.frame_count() == 20);
  const auto& t = d.agents[0];
  // The crease is a fold, not a turn: the developed path is one straight line of 0.1 m steps.
  for (int f = 1; f < 20; ++f) {
    CHECK(t.heading_rad[size_t(f)] == Approx(0).margin(1e-12));
    CHECK((t.position_m[size_t(f)] - t.position_m[size_t(f - 1)]).norm() == Approx(0.1).margin(1e-12));
  }
  // A turn about the up axis is a turn. 2D convention: heading 0 faces +Z, +90 degrees faces +X, so
  // turning from facing -X (heading -90) to facing +Z (heading 0) is +90 degrees.
  s.agents[0].forward.back() = Vec3::UnitZ();
  s.agents[0].up.back() = Vec3::UnitY();
  s.agents[0].forward[18] = -Vec3::UnitX();
  s.agents[0].up[18] = Vec3::UnitY();
  const CrowdTrajectories turned = develop_surface_trajectories(s, 10, 0.25);
  CHECK(turned.agents[0].heading_rad.back() - turned.agents[0].heading_rad[18] == Approx(M_PI / 2));
}

TEST_CASE("orient_to_surface stands a body upside down on a ceiling and sideways on a wall") {
  BodyParams params;
  const BodyShape shape = make_procedural_body(params);
  CrowdAnimation crowd;
  crowd.characters.resize(1);
  crowd.characters[0].name = "c000";
  crowd.characters[0].shape = shape;
  Pose rest = Pose::rest(shape);
  rest.root_position_m += Vec3(2, 0, 3);  // anywhere on the developed plane
  crowd.characters[0].frames = {rest, rest};
  CrowdTrajectories developed;
  developed.agents.resize(1);
  developed.agents[0].position_m = {Vec2(2, 3), Vec2(2, 3)};
  developed.agents[0].heading_rad = {0.0, 0.0};
  SurfaceTrajectories surface;
  surface.agents.resize(1);
  // Frame 0: ceiling at y = 5 (up = -Y), facing +X. Frame 1: wall x = 0 (up = +X), facing +Z.
  surface.agents[0].feet_m = {Vec3(1, 5, 1), Vec3(0, 2, 1)};
  surface.agents[0].up = {-Vec3::UnitY(), Vec3::UnitX()};
  surface.agents[0].forward = {Vec3::UnitX(), Vec3::UnitZ()};
  const auto flat = joint_positions(shape, rest);
  orient_to_surface(crowd, developed, surface);
  const auto ceiling = joint_positions(shape, crowd.characters[0].frames[0]);
  const auto wall = joint_positions(shape, crowd.characters[0].frames[1]);
  for (int j = 0; j < kJointCount; ++j) {
    // Height above the support plane is preserved, measured along the surface's up.
    const double h = flat[size_t(j)].y();
    CHECK(5 - ceiling[size_t(j)].y() == Approx(h).margin(1e-9));
    CHECK(wall[size_t(j)].x() == Approx(h).margin(1e-9));
  }
  // Facing: the rest pose faces +Z on the plane, so the nose direction maps to the surface forward.
  const Vec3 face_ceiling = crowd.characters[0].frames[0].local_rotations[0] * Vec3::UnitZ();
  const Vec3 face_wall = crowd.characters[0].frames[1].local_rotations[0] * Vec3::UnitZ();
  CHECK(face_ceiling.isApprox(Vec3::UnitX(), 1e-9));
  CHECK(face_wall.isApprox(Vec3::UnitZ(), 1e-9));
  // Mismatched inputs are refused.
  surface.agents[0].up[1] = Vec3(1, 1, 0);
  CHECK_THROWS_AS(orient_to_surface(crowd, developed, surface), InputError);
}

TEST_CASE("a manifold scenario animates walkers standing on the floor and the wall, never through them") {
  const CrowdModel model = GENERATE(CrowdModel::social, CrowdModel::orca);
  INFO("model " << kind_name(model));
  const ExperimentSpec spec = manifold_spec("floor_wall", model, 12, test::kSanitized ? 0.6 : 2.0);
  const ManifoldScenario m = generate_manifold_scenario(spec, condition(5));
  REQUIRE(m.surface.agents.size() == 12);
  REQUIRE(m.result.trajectories.frame_count() == static_cast<int>(std::lround(spec.duration_s * spec.fps)));
  CHECK_FALSE(m.result.environment.ground_plane);
  REQUIRE(m.result.environment.meshes.size() == 1);
  AnimationContext ctx;
  ctx.scenario = ScenarioKind::manifold;
  ctx.seed = 5;
  CrowdAnimation crowd = animate_crowd(m.result.trajectories, m.result.environment, spec.animation, ctx);
  const CrowdAnimation flat = crowd;  // animated on the developed plane y = 0
  orient_to_surface(crowd, m.result.trajectories, m.surface);
  validate_crowd(crowd, "test");
  int on_wall = 0, on_floor = 0;
  for (size_t i = 0; i < crowd.characters.size(); ++i)
    for (size_t f = 0; f < crowd.characters[i].frames.size(); ++f) {
      const Vec3 feet = m.surface.agents[i].feet_m[f];
      const Vec3 up = m.surface.agents[i].up[f];
      // Feet on the surface: the floor y = 0 (x >= 0) or the wall x = 0 (y >= 0).
      CHECK(std::min(std::abs(feet.x()), std::abs(feet.y())) < 1e-6);
      const bool floor = feet.y() < 1e-6 && feet.x() > 0.6, wall = feet.x() < 1e-6 && feet.y() > 0.6;
      if (!floor && !wall) continue;  // near the crease the body leans: checked by the head test only
      (floor ? on_floor : on_wall)++;
      const WorldCapsules caps = world_capsules(crowd.characters[i].shape, crowd.characters[i].frames[f]);
      const WorldCapsules flat_caps = world_capsules(flat.characters[i].shape, flat.characters[i].frames[f]);
      double deepest = 0, deepest_flat = 0;
      for (int k = 0; k < kJointCount; ++k) {
        const Capsule& c = caps[size_t(k)];
        for (const Vec3& e : {c.a, c.b}) deepest = std::min(deepest, (floor ? e.y() : e.x()) - c.radius_m);
        for (const Vec3& e : {flat_caps[size_t(k)].a, flat_caps[size_t(k)].b})
          deepest_flat = std::min(deepest_flat, e.y() - c.radius_m);
      }
      INFO("agent " << i << " frame " << f << (floor ? " floor" : " wall"));
      // No body part sinks into the surface it stands on deeper than the walk's own foot plant on flat
      // ground (the mapping is rigid), and that is a few centimetres at most.
      CHECK(deepest == Approx(deepest_flat).margin(1e-6));
      CHECK(deepest > -0.05);
      const Vec3 head = joint_positions(crowd.characters[i].shape, crowd.characters[i].frames[f])[kHead];
      const double stature = crowd.characters[i].shape.params.height_m;
      CHECK((head - feet).dot(up) > 0.75 * stature);  // standing along the surface normal
      CHECK((floor ? head.y() : head.x()) > 0.75 * stature);
    }
  CHECK(on_floor > 0);
  CHECK(on_wall > 0);
}

TEST_CASE("a manifold scenario is deterministic and refuses crowd models it cannot run") {
  const ExperimentSpec spec = manifold_spec("floor_ceiling", CrowdModel::orca, 10, 0.5);
  const ManifoldScenario a = generate_manifold_scenario(spec, condition(9));
  const ManifoldScenario b = generate_manifold_scenario(spec, condition(9));
  const ManifoldScenario c = generate_manifold_scenario(spec, condition(10));
  for (size_t i = 0; i < a.surface.agents.size(); ++i)
    CHECK(a.surface.agents[i].feet_m == b.surface.agents[i].feet_m);
  CHECK(a.surface.agents[0].feet_m != c.surface.agents[0].feet_m);
  // The spec loader refuses the cost model for a manifold scenario (tests/spec); here it is a precondition.
  CHECK_THROWS_AS(
      generate_manifold_scenario(manifold_spec("floor_ceiling", CrowdModel::cost, 10, 0.5), condition(1)),
      std::logic_error);
  CHECK_THROWS_AS(
      generate_manifold_scenario(manifold_spec("no_such_scene", CrowdModel::orca, 10, 0.5), condition(1)),
      InputError);
  CHECK_THROWS_AS(
      generate_manifold_scenario(manifold_spec("floor_ceiling", CrowdModel::orca, 0, 0.5), condition(1)),
      InputError);
}

}  // namespace test_manifold_scenario
