// Stance-foot drift, foot pops, ground penetration and floating of the feet
// (framework/metrics/foot_contact_quality.hpp) on hand-made animations whose answers are known.
#include <algorithm>
#include <catch2/catch.hpp>
#include <functional>
#include <memory>

#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/foot_contact_quality.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_foot_contact_quality {

using namespace crowdlab;

namespace {

constexpr int kFrames = 40;

/// One character standing still in its rest pose (both feet planted), with the root at
/// root_x(f) along x and raised by lift(f) on frame f.
CrowdAnimation standing(const std::function<double(int)>& root_x, const std::function<double(int)>& lift) {
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  CharacterAnimation c;
  c.name = "c000";
  c.shape = make_procedural_body({Sex::kFemale, 1.65, 1.0});
  for (int f = 0; f < kFrames; ++f) {
    Pose p = Pose::rest(c.shape);
    p.root_position_m = Vec3(root_x(f), c.shape.pelvis_height_m() + lift(f), 0.0);
    c.frames.push_back(p);
  }
  crowd.characters.push_back(c);
  return crowd;
}

double zero(int) {
  return 0.0;
}

/// Lowest point of the rest pose's foot capsules (m).
double rest_sole(const CharacterAnimation& c) {
  const WorldCapsules caps = world_capsules(c.shape, c.frames[0]);
  double y = 1e9;
  for (int b : {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot}) {
    const Capsule& k = caps[static_cast<size_t>(b)];
    y = std::min(y, std::min(k.a.y(), k.b.y()) - k.radius_m);
  }
  return y;
}

}  // namespace

TEST_CASE("a copy of the input has no drift, pops, floating or extra ground penetration") {
  const CrowdAnimation in = standing(zero, zero);
  const FootContactQuality q = measure_foot_contact_quality(in, in);
  CHECK(q.contact_frames == 4 * (kFrames - 1));  // four foot joints, planted from frame 1 on
  CHECK(q.stance_drift_max_m == 0.0);
  CHECK(q.foot_pops == 0);
  CHECK(q.pop_excess_max_m == Approx(0.0).margin(1e-12));
  CHECK(q.float_max_m == 0.0);
  CHECK(q.ground_penetration_max_m == Approx(std::max(0.0, -rest_sole(in.characters[0]))));
  CHECK(q.ground_penetration_added_max_m == 0.0);
}

TEST_CASE("a planted foot sliding 2 mm per frame drifts by the slide, a slow slide is no pop") {
  const CrowdAnimation in = standing(zero, zero);
  const CrowdAnimation out = standing([](int f) { return 0.002 * std::clamp(f - 10, 0, 10); }, zero);
  const FootContactQuality q = measure_foot_contact_quality(in, out);
  CHECK(q.stance_drift_max_m == Approx(0.020));
  // 4 joints x 39 contact frames, of which 4 x 19 are 20 mm away: the p99 is the full slide.
  CHECK(q.stance_drift_p99_m == Approx(0.020));
  CHECK(q.foot_pops == 0);
  CHECK(q.pop_excess_max_m == Approx(0.002));
  // The whole-clip measure reports the same under its old name.
  CHECK(measure_correction_quality(in, out).foot_skate_max_m == Approx(0.020));
}

TEST_CASE("a foot jumping 8 cm in one frame is a pop on each foot joint, 4 cm is not") {
  const CrowdAnimation in = standing(zero, zero);
  const FootContactQuality jump =
      measure_foot_contact_quality(in, standing([](int f) { return f >= 20 ? 0.08 : 0.0; }, zero));
  CHECK(jump.foot_pops == 4);
  CHECK(jump.pop_frames == std::vector<int>{20});
  CHECK(jump.pop_excess_max_m == Approx(0.08));
  CHECK(jump.stance_drift_max_m == Approx(0.08));
  const FootContactQuality small =
      measure_foot_contact_quality(in, standing([](int f) { return f >= 20 ? 0.04 : 0.0; }, zero));
  CHECK(small.foot_pops == 0);
  CHECK(small.pop_excess_max_m == Approx(0.04));
}

TEST_CASE("a pop is measured against the input's own motion: a walking input is not a pop") {
  // The input's root moves 6 cm per frame (1.8 m/s), the output's too: no excess, no contact.
  const auto walk = [](int f) { return 0.06 * f; };
  const CrowdAnimation in = standing(walk, zero);
  const FootContactQuality same = measure_foot_contact_quality(in, in);
  CHECK(same.foot_pops == 0);
  CHECK(same.contact_frames == 0);
  // The output stands still while the input walks: it moves less, which is no pop either.
  CHECK(measure_foot_contact_quality(in, standing(zero, zero)).foot_pops == 0);
}

TEST_CASE("feet lowered into the ground and lifted during stance are measured") {
  const CrowdAnimation in = standing(zero, zero);
  const double sole = rest_sole(in.characters[0]);
  const FootContactQuality sunk = measure_foot_contact_quality(in, standing(zero, [](int) { return -0.05; }));
  CHECK(sunk.ground_penetration_max_m == Approx(0.05 - sole));
  CHECK(sunk.ground_penetration_p99_m == Approx(0.05 - sole));
  CHECK(sunk.float_max_m == 0.0);
  const FootContactQuality lifted =
      measure_foot_contact_quality(in, standing(zero, [](int f) { return f >= 30 ? 0.03 : 0.0; }));
  CHECK(lifted.float_max_m == Approx(0.03));
  CHECK(lifted.float_p99_m == Approx(0.03));
  CHECK(lifted.ground_penetration_max_m == Approx(std::max(0.0, -sole)));
}

TEST_CASE("the part of a foot capsule below the rendered floor at rest is proxy: the depth discounts it") {
  // A body with a rendered mesh whose lowest rest vertex (its floor) is the foot capsules' lowest point,
  // then the foot capsules grown 3 cm (as a capsule fitted around a shoe wider than the foot): standing as
  // at rest it is not 3 cm below the ground, and sunk 2 cm it is 2 cm below.
  CrowdAnimation in = standing(zero, zero);
  CharacterAnimation& c = in.characters[0];
  const double sole = rest_sole(c);
  auto mesh = std::make_shared<SkinnedMesh>();
  const BoneTransforms bones = forward_kinematics(c.shape, Pose::rest(c.shape));
  const Vec3 pelvis = bones[kPelvis].translation;  // the mesh's rest frame is the rest pose's
  for (const Vec3& v : {Vec3(0.1, sole, 0.0), Vec3(-0.1, sole, 0.0), Vec3(0.0, sole, 0.1)}) {
    mesh->rest_vertices_m.push_back(v - Vec3(0.0, c.frames[0].root_position_m.y(), 0.0) + pelvis);
    mesh->joints.push_back({0, 0, 0, 0});
    mesh->weights.push_back({1.0, 0.0, 0.0, 0.0});
  }
  mesh->triangles.emplace_back(0, 1, 2);
  mesh->rest_joints_m[kPelvis] = pelvis;
  c.mesh = mesh;
  const FootContactQuality plain = measure_foot_contact_quality(in, in);
  CHECK(plain.ground_penetration_max_m == Approx(std::max(0.0, -sole)).margin(1e-9));
  CrowdAnimation fat = in;
  for (int b : {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot})
    fat.characters[0].shape.capsules[static_cast<size_t>(b)].radius_m += 0.03;
  CHECK(measure_foot_contact_quality(fat, fat).ground_penetration_max_m ==
        Approx(std::max(0.0, -sole)).margin(1e-9));
  CrowdAnimation sunk = fat;
  for (Pose& p : sunk.characters[0].frames) p.root_position_m.y() -= 0.02;
  CHECK(measure_foot_contact_quality(fat, sunk).ground_penetration_max_m == Approx(0.02 - sole).margin(1e-9));
  CHECK(measure_foot_contact_quality(fat, sunk).ground_penetration_added_max_m == Approx(0.02).margin(1e-9));
  // An input with the body's own capsules corrected into one with the grown ones (`correct --fit-proxies`):
  // the same soles, so nothing added and nothing floating.
  const FootContactQuality refitted = measure_foot_contact_quality(in, fat);
  CHECK(refitted.ground_penetration_added_max_m == Approx(0.0).margin(1e-9));
  CHECK(refitted.float_max_m == Approx(0.0).margin(1e-9));
  CHECK(measure_foot_contact_quality(fat, in).float_max_m == Approx(0.0).margin(1e-9));
  // Without the mesh the grown capsules are the feet: 3 cm deeper.
  fat.characters[0].mesh = nullptr;
  CHECK(measure_foot_contact_quality(fat, fat).ground_penetration_max_m == Approx(0.03 - sole).margin(1e-9));
}

TEST_CASE("feet the input itself puts below the ground count only for what the correction adds") {
  // The input's soles 14 mm below y = 0 on every frame (the corridor clips' input feet, issue 27).
  const double sole = rest_sole(standing(zero, zero).characters[0]);
  const auto at = [sole](double sole_m) { return [sole, sole_m](int) { return sole_m - sole; }; };
  const CrowdAnimation in = standing(zero, at(-0.014));
  const FootContactQuality same = measure_foot_contact_quality(in, in);
  CHECK(same.ground_penetration_max_m == Approx(0.014));
  CHECK(same.ground_penetration_added_max_m == 0.0);
  CHECK(same.ground_penetration_added_p99_m == 0.0);
  // 6 mm deeper than the input: the absolute measure reads 20 mm, the added one 6 mm.
  const FootContactQuality deeper = measure_foot_contact_quality(in, standing(zero, at(-0.020)));
  CHECK(deeper.ground_penetration_max_m == Approx(0.020));
  CHECK(deeper.ground_penetration_added_max_m == Approx(0.006));
  CHECK(deeper.ground_penetration_added_p99_m == Approx(0.006));
  // Lifted 10 mm (still 4 mm below y = 0): nothing added.
  CHECK(measure_foot_contact_quality(in, standing(zero, at(-0.004))).ground_penetration_added_max_m == 0.0);
  // An input foot above the ground counts from y = 0, not from the input's height: 5 mm up in the input,
  // 3 mm below in the output adds 3 mm.
  const FootContactQuality from_ground =
      measure_foot_contact_quality(standing(zero, at(0.005)), standing(zero, at(-0.003)));
  CHECK(from_ground.ground_penetration_added_max_m == Approx(0.003));
  CHECK(from_ground.ground_penetration_max_m == Approx(0.003));
}

TEST_CASE("the deepest added foot and the largest pop are named by character, joint and frame") {
  // Session 23: the corridor's 466 mm foot was a number without a place; the JSON now names it.
  CrowdAnimation in = standing(zero, zero);
  in.characters.push_back(in.characters[0]);
  CrowdAnimation out = in;
  // The second character's body sinks 3 cm on frame 25 only and jumps 8 cm along x from frame 12 on.
  out.characters[1] =
      standing([](int f) { return f >= 12 ? 0.08 : 0.0; }, [](int f) { return f == 25 ? -0.03 : 0.0; })
          .characters[0];
  const FootContactQuality q = measure_foot_contact_quality(in, out);
  CHECK(q.ground_added_worst_character == 1);
  CHECK(q.ground_added_worst_frame == 25);
  CHECK((q.ground_added_worst_joint == kLeftAnkle || q.ground_added_worst_joint == kRightAnkle));
  CHECK(q.pop_worst_character == 1);
  CHECK(q.pop_worst_frame == 12);
  const FootContactQuality none = measure_foot_contact_quality(in, in);
  CHECK(none.ground_added_worst_character == -1);
}

}  // namespace test_foot_contact_quality
