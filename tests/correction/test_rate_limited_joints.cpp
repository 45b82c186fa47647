// Rate-limited joints (issue 27, session 15; framework/correction/stage_free_joints.cpp,
// CorrectorParams::rate_limited_joints): an engaged joint of the set turns at most
// free_joint_return_radps from its last deviation after the Newton step, and in the depenetration pass it
// takes no part once that turn is used, so it never flips (at 30 fps at most 19.5 deg within 3 frames,
// under the flip measure's 20). Session 15 added the head and shoulders (neck, head, collars, upper arms):
// the stationary crowd's last flips, turned by the Newton step (docs/correction.md).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "framework/core/body_shape.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/corrector_step.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_rate_limited_joints {

using namespace crowdlab;

namespace {

/// The deviation (rad) joint j keeps after the step's release when the solve turned it by turn_rad, and
/// what the depenetration pass may still turn it (rad).
struct Kept {
  double deviation_rad = 0.0, left_rad = 0.0;
};

/// One standing body with every joint engaged (in contact) and no deviation so far, whose joint j the
/// solve turned by turn_rad about its x axis.
Kept after_a_fast_turn(BoneMask limited, int j, double turn_rad) {
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  CorrectorParams params;
  params.rate_limited_joints = limited;
  const CorrectorModel model = make_corrector_model({shape}, params, {}, 30);
  CorrectorState s;
  s.step_index = 5;
  s.target = {Pose::rest(shape)};
  s.output_deviation.assign(kJointCount, Quat::Identity());
  s.engaged_until.assign(kJointCount, 100);
  Pose pose = Pose::rest(shape);
  pose.local_rotations[static_cast<size_t>(j)] = Quat(Eigen::AngleAxisd(turn_rad, Vec3::UnitX()));
  std::array<double, kJointCount> left{};
  rotation_left(model, s, 0, pose, left);
  release_free_joints(model, s, 0, pose);
  return {pose.local_rotations[static_cast<size_t>(j)].angularDistance(Quat::Identity()),
          left[static_cast<size_t>(j)]};
}

}  // namespace

TEST_CASE(
    "correction: engaged heads, necks, collars and shoulders turn at most the rate per step and take no part "
    "in the pass once it is used",
    "[correction][rate_limit]") {
  // The stationary crowd at 6.66 /m^2 (3 s): the Newton step turned heads and shoulders by 20-26 deg within
  // 3 frames (session 14's trace), 21 flips. A step that turns such a joint by 0.5 rad (29 deg) keeps one
  // step's rate of it (6.5 deg at 30 fps), and the pass gets weight 0 for it; out of the set, the joint keeps
  // the whole turn and the pass may turn it further.
  const double turn = 0.5;
  for (int j : {kNeck, kHead, kLeftCollar, kRightCollar, kLeftShoulder, kRightShoulder}) {
    INFO(joint_name(j));
    const Kept limited = after_a_fast_turn(kDefaultRateLimitedJoints, j, turn);
    const double step = CorrectorParams{}.free_joint_return_radps / 30.0;
    CHECK(limited.deviation_rad == Approx(step).margin(1e-9));
    CHECK(limited.left_rad == 0.0);
    const Kept free =
        after_a_fast_turn(kDefaultRateLimitedJoints & ~(kHeadJoints | kShoulderJoints), j, turn);
    CHECK(free.deviation_rad == Approx(turn).margin(1e-9));
    CHECK(free.left_rad == std::numeric_limits<double>::infinity());
  }
  // The trunk and the legs are not in the set: they carry the pushes (docs/correction.md, session 15).
  for (int j : {kSpine2, kLeftHip, kLeftKnee}) {
    INFO(joint_name(j));
    CHECK(after_a_fast_turn(kDefaultRateLimitedJoints, j, turn).deviation_rad == Approx(turn).margin(1e-9));
  }
}

TEST_CASE("correction: joint sets are read from group and joint names, and written back",
          "[correction][rate_limit]") {
  CHECK(parse_joint_set("none") == 0);
  CHECK(parse_joint_set("light,elbows,head,shoulders") == kDefaultRateLimitedJoints);
  CHECK(parse_joint_set("knees,right_hip") == joint_set({kLeftKnee, kRightKnee, kRightHip}));
  CHECK(joint_set_name(joint_set({kLeftKnee, kRightKnee, kRightHip})) == "knees,right_hip");
  CHECK(parse_joint_set(joint_set_name(kAllBones)) == kAllBones);
  CHECK(joint_set_name(0) == "none");
  CHECK_THROWS_AS(parse_joint_set("light,elbow"), InputError);
  CHECK_THROWS_WITH(parse_joint_set("knees,,hips"), Catch::Contains("''"));
}

}  // namespace test_rate_limited_joints
