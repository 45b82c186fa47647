// prepare_frame (stimuli/frame_plan.hpp): the CPU half of a frame, tested without OpenGL.
#include <catch2/catch.hpp>

#include "framework/core/capsule_box.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/mesh_overlap.hpp"
#include "stimuli/frame_plan.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "tests/support/two_sphere_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_frame_plan {

using namespace crowdlab;
using namespace crowdlab::stimuli;

namespace {

/// The scene prepare_frame reads, built as Renderer::load_crowd builds it, with one made-up level of
/// detail set per character (two levels: 1 cm and 5 cm error).
struct TestScene {
  std::vector<LodLevel> levels{{11, 0.01, 3, {}}, {22, 0.05, 3, {}}};
  FrameScene scene;
  explicit TestScene(const CrowdAnimation& crowd, int height_px = 1080) {
    for (const CharacterAnimation& c : crowd.characters) {
      scene.inverse_rest.push_back(inverse_rest_transforms(c.shape));
      scene.lod_sets.push_back(&levels);
    }
    scene.boxes = crowd.environment.boxes;
    scene.bounds_lo = Vec3(-4, 0, -4);
    scene.bounds_hi = Vec3(4, 2, 4);
    scene.height_px = height_px;
  }
};

Camera front_camera() {
  Camera c;
  c.eye = Vec3(0, 1.6, -8);
  c.target = Vec3(0, 1, 0);
  return c;
}

}  // namespace

TEST_CASE("prepare_frame: skin matrices are identities at the rest pose and move with the root") {
  SyntheticCrowdOptions o;
  o.characters = 2;
  o.frames = 2;
  CrowdAnimation crowd = make_synthetic_crowd(o);
  for (CharacterAnimation& c : crowd.characters) c.frames[0] = Pose::rest(c.shape);
  crowd.characters[1].frames[1] = Pose::rest(crowd.characters[1].shape);
  crowd.characters[1].frames[1].root_position_m += Vec3(0.5, 0, 0);
  const TestScene t(crowd);
  FramePlan plan;
  prepare_frame(crowd, 0, front_camera(), {}, t.scene, plan);
  REQUIRE(plan.skin_matrices.size() == 2 * kJointCount * 16);
  for (std::size_t k = 0; k < plan.skin_matrices.size(); k += 16) {
    const Eigen::Map<const Eigen::Matrix4f> m(&plan.skin_matrices[k]);
    CHECK((m - Eigen::Matrix4f::Identity()).cwiseAbs().maxCoeff() < 1e-4f);
  }
  prepare_frame(crowd, 1, front_camera(), {}, t.scene, plan);
  for (int j = 0; j < kJointCount; ++j) {  // character 1: every bone translated by the root's 0.5 m
    const Eigen::Map<const Eigen::Matrix4f> m(&plan.skin_matrices[(kJointCount + j) * 16]);
    CHECK(m.block<3, 3>(0, 0).isIdentity(1e-4f));
    CHECK(m(0, 3) == Approx(0.5).margin(1e-4));
  }
  CHECK_THROWS_AS(prepare_frame(crowd, 2, front_camera(), {}, t.scene, plan), InputError);
}

TEST_CASE("prepare_frame: near-to-far order, coarser levels of detail far away, cut-away boxes") {
  SyntheticCrowdOptions o;
  o.characters = 16;
  o.frames = 1;
  o.corridor_walls = true;
  o.walk_speed_mps = 1.0;
  const CrowdAnimation crowd = make_synthetic_crowd(o);
  const TestScene t(crowd, 240);  // a small image: 5 cm spans under 6 pixels beyond a few metres
  const Camera camera = front_camera();
  FramePlan plan;
  prepare_frame(crowd, 0, camera, {}, t.scene, plan);
  REQUIRE(plan.order.size() == 16);
  double last = 0;
  for (const std::size_t i : plan.order) {
    const double d = (crowd.characters[i].frames[0].root_position_m - camera.eye).norm();
    CHECK(d >= last);
    last = d;
  }
  const double pixel_m_per_m = 2.0 * std::tan(0.5 * camera.fov_y_deg * std::numbers::pi / 180.0) / 240;
  for (std::size_t i = 0; i < 16; ++i) {
    const double d = (crowd.characters[i].frames[0].root_position_m - camera.eye).norm();
    CHECK(plan.mesh[i] == (0.05 <= SceneOptions{}.lod_pixels * d * pixel_m_per_m ? 22u : 11u));
  }
  // Walls along the path, seen from the front: neither hides anyone. From the side, the near one does.
  REQUIRE(crowd.environment.boxes.size() >= 2);
  for (const char hidden : plan.box_hidden) CHECK(hidden == 0);
  Camera side;
  side.eye = Vec3(-20, 1.2, 0);
  side.target = Vec3(0, 1, 0);
  prepare_frame(crowd, 0, side, {}, t.scene, plan);
  int hidden = 0;
  for (const char h : plan.box_hidden) hidden += h;
  CHECK(hidden >= 1);
  SceneOptions empty;
  empty.characters = false;
  prepare_frame(crowd, 0, camera, empty, t.scene, plan);
  CHECK(plan.order.empty());
}

TEST_CASE("prepare_frame: overlap candidates are exactly the capsules of others whose boxes meet") {
  SyntheticCrowdOptions o;
  o.characters = 9;
  o.frames = 1;
  o.spacing_m = 0.4;  // neighbours interpenetrate
  const CrowdAnimation crowd = make_synthetic_crowd(o);
  const TestScene t(crowd);
  SceneOptions options;
  FramePlan plan;
  prepare_frame(crowd, 0, front_camera(), options, t.scene, plan);
  CHECK(plan.capsules.empty());  // only in overlap mode
  for (const int c : plan.cap_count) CHECK(c == 0);
  options.overlap = true;
  prepare_frame(crowd, 0, front_camera(), options, t.scene, plan);
  std::vector<WorldCapsules> world;
  for (const CharacterAnimation& c : crowd.characters) world.push_back(world_capsules(c.shape, c.frames[0]));
  int total = 0;
  for (std::size_t a = 0; a < world.size(); ++a) {
    int expected = 0;
    for (std::size_t b = 0; b < world.size(); ++b) {
      if (a == b || !capsules_box(world[a]).overlaps(capsules_box(world[b]))) continue;
      for (const Capsule& c : world[b]) expected += capsule_box(c).overlaps(capsules_box(world[a])) ? 1 : 0;
    }
    CAPTURE(a);
    CHECK(plan.cap_count[a] == expected);
    // The own capsules come first: the first is this character's own first capsule.
    CHECK(plan.capsules[8 * static_cast<std::size_t>(plan.own_offset[a]) + 3] ==
          static_cast<float>(world[a][0].radius_m));
    total += expected;
  }
  CHECK(total > 0);
  CHECK(plan.capsules.size() == 8 * (world.size() * world[0].size() + static_cast<std::size_t>(total)));
}

TEST_CASE("prepare_frame: overlap mode flags the drawn vertices inside another character's rendered mesh") {
  // Spheres of 1.2 m around pelvises 2 m apart: they overlap, the capsules do not (tests/support).
  constexpr double kRadius = 1.2, kApart = 2.0;
  const CrowdAnimation crowd = test::two_sphere_crowd(kApart, kRadius, 1);
  // The level drawn is the mesh itself, as the renderer keeps it (bind pose, pelvis-skinned, weight 255).
  auto vertices = std::make_shared<std::vector<MannequinVertex>>();
  for (const Vec3& p : crowd.characters[0].mesh->rest_vertices_m) {
    MannequinVertex v{};
    v.position = {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())};
    v.weights = {255, 0, 0, 0};
    vertices->push_back(v);
  }
  TestScene t(crowd);
  t.levels = {{11, 0.0, 3, vertices}};
  SceneOptions options;
  FramePlan plan;
  prepare_frame(crowd, 0, front_camera(), options, t.scene, plan);
  CHECK(plan.inside.empty());  // only in overlap mode
  options.overlap = true;
  prepare_frame(crowd, 0, front_camera(), options, t.scene, plan);
  REQUIRE(plan.inside_offset.size() == 2);
  REQUIRE(plan.inside.size() == 2 * vertices->size());
  int flagged = 0, checked = 0;
  for (int a = 0; a < 2; ++a) {
    const Vec3 own = crowd.characters[static_cast<size_t>(a)].frames[0].root_position_m;
    const Vec3 other = crowd.characters[static_cast<size_t>(1 - a)].frames[0].root_position_m;
    CHECK(plan.cap_count[static_cast<size_t>(a)] == 0);  // tested on the surface, not the capsules
    for (std::size_t v = 0; v < vertices->size(); ++v) {
      const Vec3 p = own + (crowd.characters[0].mesh->rest_vertices_m[v] -
                            crowd.characters[0].mesh->rest_joints_m[kPelvis]);
      const double d = (p - other).norm() - kRadius;
      // Within the polygon's sagitta (3 mm) of the other sphere, or of the inside test's depth bound.
      if (std::abs(d) < 0.01 || std::abs(d + kMaxBodyDepth_m) < 0.01) continue;
      ++checked;
      const float f = plan.inside[static_cast<std::size_t>(plan.inside_offset[static_cast<size_t>(a)]) + v];
      CAPTURE(a, v, d);
      CHECK(f == (d < 0.0 && d > -kMaxBodyDepth_m ? 1.0f : 0.0f));
      flagged += f > 0.5f;
    }
  }
  CHECK(flagged > 0);
  CHECK(checked > static_cast<int>(vertices->size()));
  // Apart, nothing is flagged.
  const CrowdAnimation apart = test::two_sphere_crowd(3.0, kRadius, 1);
  prepare_frame(apart, 0, front_camera(), options, t.scene, plan);
  for (const float f : plan.inside) CHECK(f == 0.0f);
}

}  // namespace test_frame_plan
