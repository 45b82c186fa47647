// Procedural walking: foot skate, IK round trips, gait relations, determinism, arbitrary paths.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/animation/clip_loop.hpp"
#include "framework/animation/dance_animation.hpp"
#include "framework/animation/foot_skate.hpp"
#include "framework/animation/gait_parameters.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/animation/walk_animation.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/seed.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_walk {

using namespace crowdlab;

namespace {
AgentTrajectory straight_line(double speed, double seconds, double fps, double heading = 0.0) {
  AgentTrajectory t;
  const int n = static_cast<int>(seconds * fps);
  for (int k = 0; k < n; ++k) {
    const double s = speed * k / fps;
    t.position_m.emplace_back(s * std::sin(heading), s * std::cos(heading));
    t.heading_rad.push_back(heading);
  }
  return t;
}

AgentTrajectory circle(double speed, double radius, double seconds, double fps) {
  AgentTrajectory t;
  const int n = static_cast<int>(seconds * fps);
  for (int k = 0; k < n; ++k) {
    const double a = speed * k / fps / radius;
    t.position_m.emplace_back(radius * (1 - std::cos(a)), radius * std::sin(a));
    t.heading_rad.push_back(std::atan2(std::sin(a), std::cos(a)));
  }
  return t;
}

double min_joint_height(const BodyShape& s, const std::vector<Pose>& frames) {
  double lo = 1e9;
  for (const Pose& p : frames)
    for (const Vec3& j : joint_positions(s, p)) lo = std::min(lo, j.y());
  return lo;
}
}  // namespace

TEST_CASE("gait relations: cadence and step length follow the walk ratio and multiply to the speed") {
  for (double v = 0.5; v <= 1.8001; v += 0.1) {
    const GaitParameters g = gait_parameters(v, 1.70);
    CHECK(g.step_length_m * g.cadence_steps_per_min / 60.0 == Approx(v).epsilon(1e-9));
    CHECK(g.step_length_m / g.cadence_steps_per_min == Approx(kWalkRatioAt170).epsilon(1e-9));
  }
  const GaitParameters free = gait_parameters(1.3, 1.70);
  CHECK(free.cadence_steps_per_min == Approx(110).margin(3));  // Murray 1964 / Grieve & Gear 1966
  CHECK(free.step_length_m == Approx(0.71).margin(0.03));
}

TEST_CASE("leg IK round trip: FK of the solved leg reaches the ankle target and keeps the foot rotation") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  Rng rng(7);
  for (int i = 0; i < 200; ++i) {
    Pose pose = Pose::rest(s);
    pose.root_position_m = Vec3(uniform01(rng), 0.85 + 0.1 * uniform01(rng), uniform01(rng));
    pose.local_rotations[kPelvis] = anim::yaw(6 * uniform01(rng)) * anim::roll(0.1 * (uniform01(rng) - 0.5));
    for (LegSide side : {LegSide::kLeft, LegSide::kRight}) {
      const Vec3 hip = hip_position(s, pose, side);
      const Vec3 target =
          hip + Vec3(0.5 * (uniform01(rng) - 0.5), -0.6 - 0.2 * uniform01(rng), 0.5 * (uniform01(rng) - 0.5));
      const Quat foot = anim::yaw(uniform01(rng)) * anim::pitch(0.6 * uniform01(rng));
      const double err =
          solve_leg_ik(s, pose, side, target, foot, pose.local_rotations[kPelvis] * Vec3::UnitZ());
      const BoneTransforms bones = forward_kinematics(s, pose);
      const int ankle = leg_joints(side).ankle;
      if (err == 0.0) CHECK((bones[static_cast<size_t>(ankle)].translation - target).norm() < 1e-9);
      CHECK(bones[static_cast<size_t>(ankle)].rotation.angularDistance(foot) < 1e-9);
      // Knee is a hinge: its local rotation axis is the bone's lateral (x) axis.
      const Quat knee = pose.local_rotations[static_cast<size_t>(leg_joints(side).knee)];
      const Eigen::AngleAxisd aa(knee);
      if (aa.angle() > 1e-3) CHECK(std::abs(aa.axis().x()) > 0.999);
    }
  }
}

TEST_CASE("walking at every speed 0.5-1.8 m/s: foot skate <= 1 cm, feet alternate, no ground penetration") {
  for (double v : {0.5, 0.8, 1.1, 1.4, 1.8}) {
    for (Sex sex : {Sex::kFemale, Sex::kMale}) {
      const BodyShape s = make_procedural_body({sex, sex == Sex::kMale ? 1.78 : 1.60, 1.0});
      const WalkResult w = animate_walking(s, straight_line(v, 6.0, 30.0), 30.0, walk_style_from_seed(11));
      const FootSkate skate = measure_foot_skate(s, w.frames, w.contact);
      INFO("speed " << v << " skate max " << skate.max_m << " m over " << skate.intervals << " stances");
      CHECK(skate.max_m <= 0.01);
      CHECK(w.max_ik_error_m < 1e-6);
      CHECK(skate.intervals >= 4);
      CHECK(min_joint_height(s, w.frames) > -0.005);
      // Every frame has at least one foot down (walking, not running).
      for (size_t f = 0; f < w.frames.size(); ++f) CHECK((w.contact[0][f] || w.contact[1][f]));
      // The pelvis follows the trajectory (within the lateral sway).
      const Vec3 end = w.frames.back().root_position_m;
      CHECK(std::abs(end.z() - v * (w.frames.size() - 1) / 30.0) < 0.05);
    }
  }
}

TEST_CASE("stride frequency measured from contacts matches the cadence relation") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.70, 1.0});
  const double v = 1.3, fps = 60;
  const WalkResult w = animate_walking(s, straight_line(v, 8.0, fps), fps, walk_style_from_seed(3));
  std::vector<double> strikes;
  for (size_t f = 1; f < w.frames.size(); ++f)
    if (w.contact[0][f] && !w.contact[0][f - 1]) strikes.push_back(f / fps);
  REQUIRE(strikes.size() >= 4);
  const double period = (strikes.back() - strikes.front()) / (strikes.size() - 1);
  CHECK(120.0 / period == Approx(gait_parameters(v, 1.70).cadence_steps_per_min).epsilon(0.03));
}

TEST_CASE("walking follows curved paths and turns without skating, standing agents idle in place") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.65, 1.1});
  const WalkResult w = animate_walking(s, circle(1.2, 2.0, 8.0, 30.0), 30.0, walk_style_from_seed(5));
  const FootSkate skate = measure_foot_skate(s, w.frames, w.contact);
  CHECK(skate.max_m <= 0.01);
  for (size_t f = 0; f < w.frames.size(); f += 10) {
    const double h = w.frames[f].heading_rad();
    const double expect = std::atan2(std::sin(1.2 * f / 30.0 / 2.0), std::cos(1.2 * f / 30.0 / 2.0));
    CHECK(std::abs(anim::wrap_angle(h - expect)) < 0.25);
  }
  // Standing still: both feet down the whole time, nothing moves much.
  const WalkResult idle = animate_walking(s, straight_line(0.0, 4.0, 30.0), 30.0, walk_style_from_seed(5));
  for (size_t f = 0; f < idle.frames.size(); ++f) CHECK((idle.contact[0][f] && idle.contact[1][f]));
  CHECK(measure_foot_skate(s, idle.frames, idle.contact).max_m < 1e-6);
}

TEST_CASE("start-stop walking: skate stays under 1 cm through acceleration and stopping") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.85, 0.9});
  AgentTrajectory t;
  double z = 0;
  const double fps = 30;
  for (int k = 0; k < 300; ++k) {
    const double time = k / fps;
    const double v =
        time < 2 ? 0.0 : (time < 6 ? std::min(1.5, (time - 2) * 1.0) : std::max(0.0, 1.5 - (time - 6) * 1.2));
    z += v / fps;
    t.position_m.emplace_back(0.0, z);
    t.heading_rad.push_back(0.0);
  }
  const WalkResult w = animate_walking(s, t, fps, walk_style_from_seed(9));
  CHECK(measure_foot_skate(s, w.frames, w.contact).max_m <= 0.01);
  CHECK(w.max_ik_error_m < 1e-6);
  // Ends standing on both feet.
  CHECK((w.contact[0].back() && w.contact[1].back()));
}

TEST_CASE("walking is deterministic and varies across seeds") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const AgentTrajectory t = straight_line(1.2, 3.0, 30.0, 0.7);
  const WalkResult a = animate_walking(s, t, 30.0, walk_style_from_seed(42));
  const WalkResult b = animate_walking(s, t, 30.0, walk_style_from_seed(42));
  const WalkResult c = animate_walking(s, t, 30.0, walk_style_from_seed(43));
  bool differs = false;
  for (size_t f = 0; f < a.frames.size(); ++f) {
    CHECK(a.frames[f].root_position_m == b.frames[f].root_position_m);
    for (int j = 0; j < kJointCount; ++j)
      CHECK(a.frames[f].local_rotations[static_cast<size_t>(j)].coeffs() ==
            b.frames[f].local_rotations[static_cast<size_t>(j)].coeffs());
    differs = differs || a.frames[f].local_rotations[kLeftKnee].angularDistance(
                             c.frames[f].local_rotations[kLeftKnee]) > 0.05;
  }
  CHECK(differs);
}

TEST_CASE("a shoulder reaction turns the torso toward the passing side while the legs keep walking") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const AgentTrajectory t = straight_line(1.3, 4.0, 30.0);
  std::vector<double> left(t.position_m.size(), 0.0), right;
  for (size_t f = 30; f < 90; ++f) left[f] = std::sin(3.14159265 * (f - 30) / 60.0);  // peak 1 at frame 60
  right = left;
  for (double& w : right) w = -w;
  const WalkResult plain = animate_walking(s, t, 30.0, walk_style_from_seed(1));
  const WalkResult l = animate_walking(s, t, 30.0, walk_style_from_seed(1), left);
  const WalkResult r = animate_walking(s, t, 30.0, walk_style_from_seed(1), right);
  for (const WalkResult* w : {&l, &r}) {
    CHECK(measure_foot_skate(s, w->frames, w->contact).max_m <= 0.01);
    CHECK(w->max_ik_error_m < 1e-6);
    CHECK(w->contact == plain.contact);  // same steps
  }
  // Shoulder line: left shoulder minus right shoulder, projected on the ground. Walking +Z, a
  // reaction to the left (partner on +X) moves the left shoulder back (-Z) and presents the chest.
  auto shoulder_line_yaw = [&](const Pose& p) {
    const auto jp = joint_positions(s, p);
    const Vec3 d = jp[kLeftShoulder] - jp[kRightShoulder];
    return std::atan2(-d.z(), d.x());  // > 0 when the left shoulder is behind
  };
  const double base = shoulder_line_yaw(plain.frames[60]);
  const double turned_left = shoulder_line_yaw(l.frames[60]) - base;
  const double turned_right = shoulder_line_yaw(r.frames[60]) - base;
  INFO("shoulder line rotation: left " << turned_left * 57.3 << " deg, right " << turned_right * 57.3
                                       << " deg");
  CHECK(turned_left > 25.0 * 3.14159265 / 180.0);
  CHECK(turned_right < -25.0 * 3.14159265 / 180.0);
  // Away from the reaction the pose is the plain walk.
  for (int j = 0; j < kJointCount; ++j)
    CHECK(l.frames[10].local_rotations[static_cast<size_t>(j)].angularDistance(
              plain.frames[10].local_rotations[static_cast<size_t>(j)]) < 1e-12);
}

TEST_CASE("FK round trip on generated motion (walking, standing, dancing): bones -> pose -> bones") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.58, 1.2});
  const AgentTrajectory spot = straight_line(0.0, 3.0, 30.0);
  const std::vector<std::pair<const char*, std::vector<Pose>>> motions = {
      {"walking", animate_walking(s, circle(1.0, 3.0, 3.0, 30.0), 30.0, walk_style_from_seed(2)).frames},
      {"standing", animate_walking(s, spot, 30.0, walk_style_from_seed(2)).frames},
      {"dancing", animate_dancing(s, spot, 30.0, dance_style_from_seed(2, 3.0)).frames}};
  for (const auto& [kind, frames] : motions) {
    INFO(kind);
    for (const Pose& p : frames) {
      validate_pose(p, kind);
      const BoneTransforms bones = forward_kinematics(s, p);
      const Pose back = pose_from_bone_transforms(bones);
      CHECK((back.root_position_m - p.root_position_m).norm() < 1e-12);
      for (int j = 0; j < kJointCount; ++j)
        CHECK(back.local_rotations[static_cast<size_t>(j)].angularDistance(
                  p.local_rotations[static_cast<size_t>(j)]) < 1e-9);
      const BoneTransforms again = forward_kinematics(s, back);
      for (int j = 0; j < kJointCount; ++j)
        CHECK((again[static_cast<size_t>(j)].translation - bones[static_cast<size_t>(j)].translation).norm() <
              1e-9);
    }
  }
}

TEST_CASE("procedural walking and standing idle loop without a pop through make_seamless_loop") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  auto max_step = [&](const std::vector<Pose>& frames) {
    double worst = 0;
    for (size_t k = 1; k < frames.size(); ++k) {
      const auto a = joint_positions(s, frames[k - 1]), b = joint_positions(s, frames[k]);
      for (size_t j = 0; j < a.size(); ++j) worst = std::max(worst, (a[j] - b[j]).norm());
    }
    return worst;
  };
  for (double v : {0.0, 1.3}) {
    const WalkResult w = animate_walking(s, straight_line(v, 6.0, 30.0), 30.0, walk_style_from_seed(4));
    const double cycle_frames = v > 0 ? 30.0 * 120.0 / gait_parameters(v, 1.75).cadence_steps_per_min : 60.0;
    const int first = 40, last = first + static_cast<int>(std::lround(2 * cycle_frames));
    const LoopedClip loop = make_seamless_loop(w.frames, first, last, 10);
    std::vector<Pose> played;
    for (long k = 0; k < 3 * static_cast<long>(loop.frames.size()); ++k)
      played.push_back(sample_loop(loop, k));
    const double inside = max_step(loop.frames);
    const double seam = max_step({played[loop.frames.size() - 1], played[loop.frames.size()]});
    INFO("speed " << v << ": seam step " << seam << " m, largest in-loop step " << inside << " m");
    CHECK(seam <= 1.2 * inside + 1e-4);
    // Replays continue forward along the path.
    CHECK(played.back().root_position_m.z() >
          played.front().root_position_m.z() + 2.5 * v * 2 * cycle_frames / 30.0 - 0.2);
  }
}

}  // namespace test_walk
