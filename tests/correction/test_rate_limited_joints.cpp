// Rate-limited joints (issue 27, session 15; framework/correction/stage_free_joints.cpp,
// CorrectorParams::rate_limited_joints): an engaged joint of the set turns at most
// free_joint_return_radps from its last deviation after the Newton step, and in the depenetration pass it
// takes no part once that turn is used, so it never flips (at 30 fps at most 19.5 deg within 3 frames,
// under the flip measure's 20). Session 15 added the head and shoulders (neck, head, collars, upper arms):
// the stationary crowd's last flips, turned by the Newton step (docs/correction.md). Session 16: engaged
// knees are hinges for the limit (CorrectorParams::knee_hinge): their flexion is free, what they turn off
// the hinge is limited, after the step and in the pass. Session 17 (CorrectorParams::lift_off_knees): the
// knee of a leg whose foot is not held is limited whole, and a foot held at its ball only is let go once
// its knee's flexion is far off the input's; session 18: it pivots about the ball instead, the knee
// returning at the rate (the default since).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "framework/core/body_shape.hpp"
#include "framework/core/capsule_box_distance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/corrector_step.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_rate_limited_joints {

using namespace crowdlab;

namespace {

/// After the step's release, for one standing body with every joint engaged (in contact) and no
/// deviation so far, whose joint j the solve turned by `turn` (local, in its parent frame): the joint's
/// local rotation, what the depenetration pass may still turn it (rad), and what it may still turn the
/// left knee off its hinge (rad; -1 where not so limited).
struct Released {
  Quat local = Quat::Identity();
  double left_rad = 0.0, knee_off_hinge_left_rad = 0.0;
};
Released after_the_release(const CorrectorParams& params, int j, const Quat& turn, bool feet_held = true,
                           const Quat& deviation = Quat::Identity()) {
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const CorrectorModel model = make_corrector_model({shape}, params, {}, 30);
  CorrectorState s;
  s.step_index = 5;
  s.target = {Pose::rest(shape)};
  s.output_deviation.assign(kJointCount, Quat::Identity());
  s.output_deviation[static_cast<size_t>(j)] = deviation;  // the last output's, from the input
  s.engaged_until.assign(kJointCount, 100);
  FootHold hold;
  hold.ankle = hold.ball = feet_held;
  s.foot_holds.assign(2, hold);
  Pose pose = Pose::rest(shape);
  pose.local_rotations[static_cast<size_t>(j)] = turn;
  std::array<double, kJointCount> left{};
  rotation_left(model, s, 0, pose, left);
  release_free_joints(model, s, 0, pose);
  return {pose.local_rotations[static_cast<size_t>(j)], left[static_cast<size_t>(j)],
          knee_off_hinge_left(model, s, 0, pose, kLeftKnee)};
}

/// The deviation (rad) joint j keeps after the step's release when the solve turned it by turn_rad about
/// its x axis, and what the depenetration pass may still turn it (rad).
struct Kept {
  double deviation_rad = 0.0, left_rad = 0.0;
};
Kept after_a_fast_turn(BoneMask limited, int j, double turn_rad) {
  CorrectorParams params;
  params.rate_limited_joints = limited;
  const Released r = after_the_release(params, j, Quat(Eigen::AngleAxisd(turn_rad, Vec3::UnitX())));
  return {r.local.angularDistance(Quat::Identity()), r.left_rad};
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

namespace {
/// The left knee after the release (after_the_release) with or without the hinge.
Released knee_after(bool hinge, const Quat& turn) {
  CorrectorParams params;
  params.knee_hinge = hinge;
  return after_the_release(params, kLeftKnee, turn);
}
double angle_about_x_rad(const Quat& q) {
  return 2.0 * std::atan2(q.x(), q.w());
}
}  // namespace

TEST_CASE("correction: an engaged knee keeps its flexion and turns off its hinge at most the rate per step",
          "[correction][rate_limit]") {
  // Session 16: the corridor's held knees flipped by turns off their hinge (abduction 12-16 deg per flip
  // window on 3 s clips at 6.66 /m^2, beside the flexion); session 11's limit acted on the twist about the
  // shank only. A solve that flexes the knee by 0.5 rad and turns it 0.5 rad sideways (about z) keeps the
  // flexion whole and 6.5 deg (one step's rate at 30 fps) of the sideways turn; without the hinge the
  // sideways turn stays whole.
  const double step = CorrectorParams{}.free_joint_return_radps / 30.0;
  const Quat flex(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  const Quat sideways(Eigen::AngleAxisd(0.5, Vec3::UnitZ()));
  const Released hinged = knee_after(true, sideways * flex);
  CHECK(off_hinge_part(hinged.local).angularDistance(Quat::Identity()) == Approx(step).margin(1e-9));
  CHECK(angle_about_x_rad((off_hinge_part(hinged.local).conjugate() * hinged.local).normalized()) ==
        Approx(0.5).margin(1e-9));
  CHECK(hinged.knee_off_hinge_left_rad == Approx(0.0).margin(1e-9));  // the pass may not turn it further off
  const Released flexed = knee_after(true, flex);                     // flexion alone: nothing to limit
  CHECK(flexed.local.angularDistance(flex) < 1e-9);
  CHECK(flexed.knee_off_hinge_left_rad == Approx(step).margin(1e-9));
  const Released old = knee_after(false, sideways * flex);
  CHECK(off_hinge_part(old.local).angularDistance(Quat::Identity()) > 0.45);
  CHECK(old.knee_off_hinge_left_rad < 0.0);  // not limited in the pass
}

TEST_CASE(
    "correction: a held leg pressed sideways at the shank turns its knee off the hinge at most the rate",
    "[correction][rate_limit]") {
  // Session 16: the depenetration pass separated contacts on held legs by turning the knee sideways (the
  // held foot pins the shank's lower end; session 14's trace: 14-42 deg per flip window). A body stands
  // still (feet planted and held from the second step) with a post pressing 2 cm into its left shank from
  // the side. The knee's deviation off its hinge changes by at most the rate (6.5 deg) per step with
  // the hinge, and the pass takes the shank out all the same (to its tolerance, with the hip, the
  // pelvis and the foot giving way).
  const BodyShape body = make_procedural_body({});
  const Pose pose = Pose::rest(body);
  const Capsule shank = world_capsules(body, pose)[kLeftKnee];  // from the knee to the ankle
  const Vec3 mid = 0.5 * (shank.a + shank.b);
  Environment env;
  Box post;
  post.half_extents_m = Vec3(0.05, 0.05, 0.05);
  post.center_m = Vec3(mid.x() + shank.radius_m - 0.04 + post.half_extents_m.x(), mid.y(), mid.z());
  env.boxes.push_back(post);
  REQUIRE(-capsule_box_distance(shank, post).distance_m == Approx(0.04).margin(1e-3));
  const auto run = [&](bool hinge, double& depth_m) {
    CorrectorParams params;
    params.knee_hinge = hinge;
    Corrector corrector({body}, params, env, 30);
    Quat last = Quat::Identity();
    double worst = 0.0;
    for (int f = 0; f < 15; ++f) {
      const auto out = corrector.step({pose});
      const Quat knee = out[0].local_rotations[kLeftKnee];  // the input's is the identity
      worst = std::max(
          worst, off_hinge_part((knee * last.conjugate()).normalized()).angularDistance(Quat::Identity()));
      last = knee;
      depth_m = -capsule_box_distance(world_capsules(body, out[0])[kLeftKnee], post).distance_m;
    }
    return worst;
  };
  const double step = CorrectorParams{}.free_joint_return_radps / 30.0;
  double depth_hinged = 0.0, depth_free = 0.0;
  const double hinged = run(true, depth_hinged), free = run(false, depth_free);
  INFO("largest off-hinge knee turn per step: hinge "
       << hinged << " rad, without " << free << " rad; shank depth after 15 steps " << depth_hinged << " / "
       << depth_free << " m");
  CHECK(hinged <= step + 1e-6);
  CHECK(free > step);
  CHECK(depth_hinged <= 0.0055);
}

TEST_CASE(
    "correction: an engaged knee of a leg whose foot is not held returns from a large deviation at most the "
    "rate",
    "[correction][rate_limit]") {
  // Session 17: a held leg that the stance kept 15-37 deg straighter than the input's was turned back by
  // the Newton step within 1-3 frames of its lift-off (half of the corridor's knee flips at 6.66 /m^2, 3 s).
  // Once the foot is not held, no leg IK sets the knee's flexion: a knee whose last output is off the
  // input's flexion by more than 3 rate turns (19.5 deg) turns at most the rate (6.5 deg at 30 fps), all
  // of it, and the pass may turn it only what is left. Here the knee is 25 deg straighter than the input's
  // and the solve turns it back by 25 deg at once. Nearer its input (10 deg), or held, or without
  // lift_off_knees, the knee keeps what the solve gave it.
  const double step = CorrectorParams{}.free_joint_return_radps / 30.0, deg = std::numbers::pi / 180.0;
  const Quat straighter(Eigen::AngleAxisd(-25.0 * deg, Vec3::UnitX()));
  CorrectorParams params;
  params.lift_off_knees = true;  // the default since session 18
  const Released swinging = after_the_release(params, kLeftKnee, Quat::Identity(), false, straighter);
  CHECK(swinging.local.angularDistance(straighter) == Approx(step).margin(1e-9));
  CHECK(swinging.left_rad == 0.0);
  CHECK(swinging.knee_off_hinge_left_rad < 0.0);  // limited whole, not as a hinge
  const Quat near(Eigen::AngleAxisd(-10.0 * deg, Vec3::UnitX()));
  CHECK(after_the_release(params, kLeftKnee, Quat::Identity(), false, near)
            .local.angularDistance(Quat::Identity()) < 1e-9);
  const Released held = after_the_release(params, kLeftKnee, Quat::Identity(), true, straighter);
  CHECK(held.local.angularDistance(Quat::Identity()) < 1e-9);
  params.lift_off_knees = false;
  const Released session16 = after_the_release(params, kLeftKnee, Quat::Identity(), false, straighter);
  CHECK(session16.local.angularDistance(Quat::Identity()) < 1e-9);
  CHECK(session16.left_rad == std::numeric_limits<double>::infinity());
}

TEST_CASE(
    "correction: a foot held at its ball only pivots about it once its knee's flexion is far off the input's",
    "[correction][rate_limit]") {
  // Session 17 let such a ball go (the knee then returned at the rate) and the ball slid with the leg
  // (the walking corridor's skate 2.8 -> 17.2 cm). Session 18: the ball stays held and the foot pivots
  // about it (FootHold::pivot_on_ball) from 4 rate turns (26 deg at 30 fps) until the input lifts the ball;
  // at 20 deg, or without lift_off_knees, it stays an ordinary hold.
  const BodyShape shape = make_procedural_body({});
  CorrectorParams params;
  const auto rolling = [&](bool lift_off, double knee_deviation_rad, bool pivoting, bool ball_lifts) {
    params.lift_off_knees = lift_off;
    const CorrectorModel model = make_corrector_model({shape}, params, {}, 30);
    CorrectorState s = make_corrector_state(model);
    s.foot_holds[0].ball = true;  // the left foot rolls on its ball
    s.foot_holds[0].pivot_on_ball = pivoting;
    s.foot_holds[0].ball_anchor_m = Vec3(0.1, 0.02, 0.3);
    s.target_origin_old_m[kLeftFoot] = s.target_origin_m[kLeftFoot] = Vec3(0.1, 0.02, 0.3);
    if (ball_lifts) s.target_origin_m[kLeftFoot].y() += 0.01;
    s.target_origin_old_m[kLeftAnkle] = Vec3(0.1, 0.08, 0.2);
    s.target_origin_m[kLeftAnkle] = Vec3(0.1, 0.11, 0.21);  // the heel rises 3 cm in the frame
    s.output_deviation[kLeftKnee] = Quat(Eigen::AngleAxisd(-knee_deviation_rad, Vec3::UnitX()));
    update_foot_holds(model, s, 0, {Quat::Identity(), Quat::Identity()});
    CHECK(!s.foot_holds[0].ankle);
    CHECK(s.foot_holds[0].ball_anchor_m == Vec3(0.1, 0.02, 0.3));
    return std::pair{s.foot_holds[0].ball, s.foot_holds[0].pivot_on_ball};
  };
  const double deg = std::numbers::pi / 180.0;
  CHECK(rolling(true, 30.0 * deg, false, false) == std::pair{true, true});
  CHECK(rolling(true, 20.0 * deg, false, false) == std::pair{true, false});
  CHECK(rolling(true, 20.0 * deg, true, false) == std::pair{true, true});  // pivots until the ball lifts
  CHECK(rolling(true, 20.0 * deg, true, true) == std::pair{false, false});
  CHECK(rolling(false, 30.0 * deg, false, false) == std::pair{true, false});
}

TEST_CASE("correction: a foot pivoting about its held ball returns its knee at the rate, the ball kept",
          "[correction][rate_limit]") {
  // The input's left knee is bent 40 deg; the last output's is 30 deg straighter, its ball held where it
  // is. Whatever flexion the solve gives the knee (none off the input's, or still 30 deg off), hold_feet
  // leaves it 30 - 6.5 deg off the input's with the ball on its anchor: the foot turns about the ball.
  // As an ordinary hold (no pivot) the knee takes whatever the leg IK needs to re-plant the foot.
  const BodyShape shape = make_procedural_body({Sex::kMale, 1.75, 1.0});
  CorrectorParams params;
  params.lift_off_knees = true;
  const CorrectorModel model = make_corrector_model({shape}, params, {}, 30);
  const double deg = std::numbers::pi / 180.0, step = params.free_joint_return_radps / 30.0;
  Pose input = Pose::rest(shape);
  input.local_rotations[kLeftHip] = Quat(Eigen::AngleAxisd(-20.0 * deg, Vec3::UnitX()));
  input.local_rotations[kLeftKnee] = Quat(Eigen::AngleAxisd(40.0 * deg, Vec3::UnitX()));
  const Quat off(Eigen::AngleAxisd(-30.0 * deg, Vec3::UnitX()));
  Pose last = input;
  last.local_rotations[kLeftKnee] = input.local_rotations[kLeftKnee] * off;
  const BoneTransforms in_bones = forward_kinematics(shape, input),
                       last_bones = forward_kinematics(shape, last);
  const auto knee_off_after = [&](bool pivot, const Quat& solved_knee_off, Vec3& ball_m) {
    CorrectorState s = make_corrector_state(model);
    s.target = {input};
    for (size_t j = 0; j < kJointCount; ++j) {
      s.target_rotation[j] = in_bones[j].rotation;
      s.target_origin_m[j] = s.target_origin_old_m[j] = in_bones[j].translation;
    }
    for (size_t k = 0; k < 4; ++k)
      s.foot_start_m[k] = last_bones[static_cast<size_t>(kFootJointOrder[k])].translation;
    s.output_deviation[kLeftKnee] = off;
    FootHold& hold = s.foot_holds[0];
    hold.ball = true;
    hold.pivot_on_ball = pivot;
    hold.ball_anchor_m = last_bones[kLeftFoot].translation;
    hold.rotation_offset =
        (last_bones[kLeftAnkle].rotation * in_bones[kLeftAnkle].rotation.conjugate()).normalized();
    Pose pose = last;
    pose.local_rotations[kLeftKnee] = input.local_rotations[kLeftKnee] * solved_knee_off;
    hold_feet(model, s, 0, pose);
    ball_m = forward_kinematics(shape, pose)[kLeftFoot].translation;
    const Quat d =
        (input.local_rotations[kLeftKnee].conjugate() * pose.local_rotations[kLeftKnee]).normalized();
    return 2.0 * std::atan2(d.x(), d.w());
  };
  const Vec3 anchor = last_bones[kLeftFoot].translation;
  for (const Quat& solved : {Quat::Identity(), off}) {
    Vec3 ball;
    CHECK(knee_off_after(true, solved, ball) == Approx(-30.0 * deg + step).margin(0.5 * deg));
    CHECK(Vec3(ball - anchor).cwiseProduct(Vec3(1.0, 0.0, 1.0)).norm() < 0.001);
  }
  Vec3 ball;
  // The ordinary hold: the IK flexes the knee and swings the thigh (measured: 14 deg off), not at the rate.
  CHECK(std::abs(knee_off_after(false, Quat::Identity(), ball) - (-30.0 * deg + step)) > 5.0 * deg);
  CHECK(Vec3(ball - anchor).cwiseProduct(Vec3(1.0, 0.0, 1.0)).norm() < 0.001);
}

TEST_CASE("correction: a held leg pressed sideways at the knee twists its ankle at most the rate per step",
          "[correction][rate_limit]") {
  // Session 19: the depenetration pass moved knees out of contacts by turning a held leg about its
  // hip-ankle line; the held foot keeps its world rotation, so hold_feet handed that turn to the ankle
  // (session 18's trace: 22-41 deg per flip window of the corridor's ankles). A body crouches still (hips
  // and knees bent, feet flat, planted and held from the second step) with a post pressing 3 cm into the
  // side of its left knee. With held_ankle_twist_in_pass the left ankle turns about its up axis at most
  // the rate per step (6.5 deg; the pass's linearised row, so within a small slack), and the knee still
  // comes out of the post to within the pass's tolerance; without it the ankle twists faster.
  const BodyShape body = make_procedural_body({});
  Pose pose = Pose::rest(body);
  const double hip_rad = -0.4, knee_rad = 0.8;  // thigh forward, shank back: a crouch
  for (const LegSide side : {LegSide::kLeft, LegSide::kRight}) {
    const LegJoints lj = leg_joints(side);
    pose.local_rotations[static_cast<size_t>(lj.hip)] = Quat(Eigen::AngleAxisd(hip_rad, Vec3::UnitX()));
    pose.local_rotations[static_cast<size_t>(lj.knee)] = Quat(Eigen::AngleAxisd(knee_rad, Vec3::UnitX()));
    pose.local_rotations[static_cast<size_t>(lj.ankle)] =
        Quat(Eigen::AngleAxisd(-hip_rad - knee_rad, Vec3::UnitX()));  // the foot flat
  }
  const double rest_sole_m =
      foot_sole_height_m(world_capsules(body, Pose::rest(body)), leg_joints(LegSide::kLeft));
  pose.root_position_m.y() -=
      foot_sole_height_m(world_capsules(body, pose), leg_joints(LegSide::kLeft)) - rest_sole_m;
  const Capsule shank = world_capsules(body, pose)[kLeftKnee];  // from the knee down
  Environment env;
  Box post;
  post.half_extents_m = Vec3(0.05, 0.05, 0.05);
  post.center_m =
      Vec3(shank.a.x() + shank.radius_m - 0.03 + post.half_extents_m.x(), shank.a.y(), shank.a.z());
  env.boxes.push_back(post);
  const auto run = [&](bool limit, double& depth_m) {
    CorrectorParams params;
    params.held_ankle_twist_in_pass = limit;
    Corrector corrector({body}, params, env, 30);
    Quat last = pose.local_rotations[kLeftAnkle];
    double worst = 0.0;
    for (int f = 0; f < 15; ++f) {
      const auto out = corrector.step({pose});
      const Quat ankle = out[0].local_rotations[kLeftAnkle];
      Quat change = (last.conjugate() * ankle).normalized();
      if (change.w() < 0.0) change.coeffs() = -change.coeffs();
      worst = std::max(worst, std::abs(2.0 * std::atan2(change.y(), change.w())));
      last = ankle;
      depth_m = -capsule_box_distance(world_capsules(body, out[0])[kLeftKnee], post).distance_m;
    }
    return worst;
  };
  const double step = CorrectorParams{}.free_joint_return_radps / 30.0;
  double depth_limited = 0.0, depth_free = 0.0;
  const double limited = run(true, depth_limited), free = run(false, depth_free);
  INFO("largest ankle twist per step: limited "
       << limited << " rad, without " << free << " rad; knee depth after 15 steps " << depth_limited << " / "
       << depth_free << " m");
  CHECK(limited <= step + 0.002);
  CHECK(free > step + 0.01);
  CHECK(depth_limited <= 0.0055);
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
