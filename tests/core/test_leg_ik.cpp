// Least-change leg IK (core/leg_ik.hpp: reach_ankle), used by the correction stage to re-plant feet.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/core/body_shape.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/seed.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_leg_ik {

using namespace crowdlab;

namespace {
// A standing pose with a slightly bent, twisted leg (not a pure hinge), turned and tilted pelvis.
Pose bent_pose(const BodyShape& s, Rng& rng) {
  Pose pose = Pose::rest(s);
  pose.root_position_m = Vec3(uniform01(rng), 0.9, uniform01(rng));
  pose.local_rotations[kPelvis] = Quat(Eigen::AngleAxisd(6.0 * uniform01(rng), Vec3::UnitY()));
  for (int j : {kLeftHip, kRightHip, kLeftKnee, kRightKnee, kLeftAnkle, kRightAnkle}) {
    const Vec3 axis = Vec3(uniform01(rng), uniform01(rng), uniform01(rng)).normalized();
    const double angle = j == kLeftKnee || j == kRightKnee ? 0.4 : 0.15;
    pose.local_rotations[static_cast<size_t>(j)] = Quat(Eigen::AngleAxisd(angle * uniform01(rng), axis));
  }
  return pose;
}
}  // namespace

TEST_CASE("reach_ankle: a leg already on its target is left exactly as it was", "[leg_ik]") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.65, 1.0});
  Rng rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Pose before = bent_pose(s, rng);
    Pose after = before;
    const BoneTransforms bones = forward_kinematics(s, before);
    const double err =
        reach_ankle(s, after, LegSide::kLeft, bones[kLeftAnkle].translation, bones[kLeftAnkle].rotation);
    CHECK(err == 0.0);
    for (size_t j = 0; j < kJointCount; ++j)
      CHECK(after.local_rotations[j].angularDistance(before.local_rotations[j]) < 1e-7);
  }
}

TEST_CASE("reach_ankle: the ankle lands on reachable targets with the foot rotation asked for", "[leg_ik]") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  Rng rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    Pose pose = bent_pose(s, rng);
    const LegSide side = trial % 2 == 0 ? LegSide::kLeft : LegSide::kRight;
    const LegJoints lj = leg_joints(side);
    const BoneTransforms before = forward_kinematics(s, pose);
    // A planted foot the pelvis has been pushed away from by up to 5 cm.
    const Vec3 target = before[static_cast<size_t>(lj.ankle)].translation +
                        0.05 * Vec3(uniform01(rng) - 0.5, uniform01(rng) - 0.5, uniform01(rng) - 0.5);
    const Quat foot = before[static_cast<size_t>(lj.ankle)].rotation;
    const double err = reach_ankle(s, pose, side, target, foot);
    const BoneTransforms after = forward_kinematics(s, pose);
    if (err == 0.0) CHECK((after[static_cast<size_t>(lj.ankle)].translation - target).norm() < 1e-9);
    CHECK(after[static_cast<size_t>(lj.ankle)].rotation.angularDistance(foot) < 1e-9);
    // A small move is a small edit: the hip and knee turn by a few degrees, not by a re-solve.
    for (int j : {lj.hip, lj.knee})
      CHECK(after[static_cast<size_t>(j)].rotation.angularDistance(before[static_cast<size_t>(j)].rotation) <
            0.35);
    // The other leg and the pelvis are untouched.
    const LegJoints other = leg_joints(side == LegSide::kLeft ? LegSide::kRight : LegSide::kLeft);
    CHECK((after[static_cast<size_t>(other.ankle)].translation -
           before[static_cast<size_t>(other.ankle)].translation)
              .norm() < 1e-12);
  }
}

TEST_CASE("reach_ankle: an out-of-reach target straightens the leg toward it and reports the gap",
          "[leg_ik]") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  Rng rng(9);
  Pose pose = bent_pose(s, rng);
  const Vec3 hip = hip_position(s, pose, LegSide::kLeft);
  const Vec3 dir = Vec3(0.3, -1.0, 0.2).normalized();
  const double too_far = leg_length(s, LegSide::kLeft) + 0.1;
  const double err = reach_ankle(s, pose, LegSide::kLeft, hip + too_far * dir, Quat::Identity());
  // Within 0.1 mm: a knee bent a little off its hinge plane keeps that off-plane bend (the knee flexes
  // about its hinge when nearly straight), and the gap reported is the one left.
  CHECK(err == Approx(0.1).margin(1e-4));
  const Vec3 ankle = forward_kinematics(s, pose)[kLeftAnkle].translation;
  CHECK((ankle - (hip + leg_length(s, LegSide::kLeft) * dir)).norm() < 1e-4);
  CHECK((ankle - (hip + too_far * dir)).norm() == Approx(err).margin(1e-9));
}

namespace {
// The left leg of a standing body, knee nearly straight, bent by `knee` (a small rotation).
Pose nearly_straight_leg(const BodyShape& s, const Quat& knee) {
  Pose pose = Pose::rest(s);
  pose.root_position_m = Vec3(0.0, 0.95, 0.0);
  pose.local_rotations[kLeftKnee] = knee;
  return pose;
}

// The knee's local rotation after moving the ankle 3 cm up (a pushed pelvis over a held foot).
Quat knee_after_shortening(const BodyShape& s, const Quat& knee) {
  Pose pose = nearly_straight_leg(s, knee);
  const BoneTransforms bones = forward_kinematics(s, pose);
  const Vec3 target = bones[kLeftAnkle].translation + Vec3(0.0, 0.03, 0.0);
  REQUIRE(reach_ankle(s, pose, LegSide::kLeft, target, bones[kLeftAnkle].rotation) ==
          Approx(0.0).margin(1e-9));
  CHECK((forward_kinematics(s, pose)[kLeftAnkle].translation - target).norm() < 1e-9);
  return pose.local_rotations[kLeftKnee];
}

// Forward flexion: a rotation mostly about the thigh's lateral axis (+x), positive.
double forward_flexion_share(const Quat& q) {
  const Eigen::AngleAxisd aa(q);
  return aa.angle() * aa.axis().x();
}
}  // namespace

TEST_CASE("reach_ankle: a nearly straight knee flexes forward about its hinge, whatever its small bend",
          "[leg_ik]") {
  // Before issue 27's fix the knee flexed about the thigh x shank normal, which for a nearly straight
  // leg points wherever a 0.3 deg sideways bend or a 1 deg hyperextension puts it: the knee then bent
  // sideways or backward by ~15 deg, and the other way a frame later when that small bend changed
  // sign (knee and ankle flips of held feet in the corridor).
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  for (const Quat& small_bend :
       {Quat(Eigen::AngleAxisd(0.005, Vec3::UnitZ())), Quat(Eigen::AngleAxisd(-0.005, Vec3::UnitZ())),
        Quat(Eigen::AngleAxisd(-0.02, Vec3::UnitX())), Quat(Eigen::AngleAxisd(0.005, Vec3::UnitX()))}) {
    const Quat knee = knee_after_shortening(s, small_bend);
    const double angle = knee.angularDistance(Quat::Identity());
    CHECK(angle > 0.1);                                 // it had to bend (3 cm on a 0.9 m leg)
    CHECK(forward_flexion_share(knee) > 0.97 * angle);  // forward, about the hinge
  }
  // The knee answer is continuous in the input: a sideways bend of +0.3 deg and of -0.3 deg give
  // knees within a degree of each other, not mirror images.
  const Quat a = knee_after_shortening(s, Quat(Eigen::AngleAxisd(0.005, Vec3::UnitZ())));
  const Quat b = knee_after_shortening(s, Quat(Eigen::AngleAxisd(-0.005, Vec3::UnitZ())));
  CHECK(a.angularDistance(b) < 0.02);
}

}  // namespace test_leg_ik
