// The loop closure's blend (issue 28): planted feet stay where they stand while the clip's end blends
// into the loop pre-roll's poses; lifted feet and the rest of the body reach the pre-roll's poses.
// A correction run again inside the closure keeps the feet the input plants where they stood.
#include <catch2/catch.hpp>

#include "framework/core/blend_poses.hpp"
#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/penetration_depth.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/metrics/foot_contact_quality.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_loop_closure {

using namespace crowdlab;

namespace {

/// One swaying character whose left foot steps 25 cm sideways (lifted 8 cm) on frames 35-44 of 60.
CrowdAnimation stepping_character() {
  SwayingCrowdOptions o;
  o.characters = 1;
  o.frames = 60;
  CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  CharacterAnimation& c = crowd.characters[0];
  const auto ankle = static_cast<size_t>(leg_joints(LegSide::kLeft).ankle);
  for (size_t f = 35; f < c.frames.size(); ++f) {
    const BoneTransforms bones = forward_kinematics(c.shape, c.frames[f]);
    const double t = std::min(1.0, (static_cast<double>(f) - 34.0) / 10.0);  // 0.1 .. 1 over the step
    const Vec3 goal = bones[ankle].translation + Vec3(0.25 * t, 0.08 * std::sin(std::numbers::pi * t), 0.0);
    reach_ankle(c.shape, c.frames[f], LegSide::kLeft, goal, bones[ankle].rotation);
  }
  return crowd;
}

/// The clip's last `window` frames moved by `shift` (the pre-roll's output of a crowd pushed aside).
std::vector<std::vector<Pose>> shifted_end(const CrowdAnimation& crowd, int window, const Vec3& shift) {
  std::vector<std::vector<Pose>> out;
  for (const CharacterAnimation& c : crowd.characters) {
    out.emplace_back(c.frames.end() - window, c.frames.end());
    for (Pose& p : out.back()) p.root_position_m += shift;
  }
  return out;
}

}  // namespace

TEST_CASE("loop closure: the blend keeps planted feet and reaches the pre-roll's end", "[correction][loop]") {
  const CrowdAnimation input = stepping_character();
  const int window = 40;  // frames 20-59: the step lies inside
  const Vec3 shift(0.03, 0.0, 0.02);
  const auto targets = shifted_end(input, window, shift);
  CrowdAnimation closed = input;
  blend_keeping_planted_feet(input, targets, window, CorrectorParams{}, closed);
  // The plain blend (the closure before issue 28's fix) slides both planted feet by up to 3.6 cm.
  CrowdAnimation plain = input;
  for (int k = 0; k < window; ++k) {
    Pose& p = plain.characters[0].frames[static_cast<size_t>(20 + k)];
    p = blend_poses(p, targets[0][static_cast<size_t>(k)], raised_cosine(k + 1, window));
  }
  const FootContactQuality q_plain = measure_foot_contact_quality(input, plain);
  const FootContactQuality q_closed = measure_foot_contact_quality(input, closed);
  INFO("stance drift max: plain blend " << q_plain.stance_drift_max_m << " m, kept "
                                        << q_closed.stance_drift_max_m);
  CHECK(q_plain.stance_drift_max_m > 0.02);
  CHECK(q_closed.stance_drift_max_m < 0.001);
  CHECK(q_closed.foot_pops == 0);
  // The last frame is the pre-roll's: the body where it stands (the pelvis may sit lower, so that the
  // straight right leg reaches its kept foot) and the stepping foot, which moved while lifted...
  const CharacterAnimation& c = closed.characters[0];
  const auto end = joint_positions(c.shape, c.frames.back());
  const auto goal = joint_positions(c.shape, targets[0].back());
  const auto left = static_cast<size_t>(leg_joints(LegSide::kLeft).ankle);
  const auto right = static_cast<size_t>(leg_joints(LegSide::kRight).ankle);
  const Vec3 root_gap = c.frames.back().root_position_m - targets[0].back().root_position_m;
  CHECK(std::hypot(root_gap.x(), root_gap.z()) < 1e-9);
  CHECK(root_gap.y() <= 0.0);
  CHECK(root_gap.y() > -0.01);
  CHECK((end[left] - goal[left]).norm() < 1e-6);
  // ...but the right foot, planted all along, stays where the clip had it.
  const auto start = joint_positions(c.shape, input.characters[0].frames.back());
  CHECK((end[right] - start[right]).norm() < 1e-6);
  // Frames before the window are untouched.
  CHECK(closed.characters[0].frames[19].root_position_m == input.characters[0].frames[19].root_position_m);
}

TEST_CASE("loop closure: the crowd's deepest penetration matches all pairs", "[correction][loop]") {
  SwayingCrowdOptions o;
  o.characters = 12;
  o.density_per_m2 = 6.66;
  o.frames = 3;
  const CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  for (int f = 0; f < crowd.frame_count(); ++f) {
    std::vector<WorldCapsules> bodies;
    for (const CharacterAnimation& c : crowd.characters)
      bodies.push_back(world_capsules(c.shape, c.frames[static_cast<size_t>(f)]));
    double all_pairs = 0.0;
    for (size_t a = 0; a < bodies.size(); ++a)
      for (size_t b = a + 1; b < bodies.size(); ++b)
        all_pairs = std::max(all_pairs, max_penetration_depth(bodies[a], bodies[b]));
    CHECK(all_pairs > 0.0);  // the fixture at 6.66/m² collides
    CHECK(deepest_crowd_penetration(bodies) == all_pairs);
  }
}

TEST_CASE("loop closure: a foot the second correction sets down off its spot stays where it stood",
          "[correction][loop]") {
  // The left foot lands on frame 45 (stepping_character). The clip's foot lags the swing by up to 2 cm and
  // is set down 12 mm from where it stood on frame 44, as the closure's second correction did on
  // loop_seam.yaml (session 13).
  const CrowdAnimation input = stepping_character();
  CrowdAnimation clip = input;
  CharacterAnimation& c = clip.characters[0];
  const auto left = static_cast<size_t>(leg_joints(LegSide::kLeft).ankle);
  const auto right = static_cast<size_t>(leg_joints(LegSide::kRight).ankle);
  for (size_t f = 41; f < c.frames.size(); ++f) {
    const double lag_m = f < 45 ? 0.02 * (static_cast<double>(f) - 40.0) / 4.0 : 0.008;
    const BoneTransforms bones = forward_kinematics(c.shape, c.frames[f]);
    reach_ankle(c.shape, c.frames[f], LegSide::kLeft, bones[left].translation + Vec3(lag_m, 0.0, 0.0),
                bones[left].rotation);
  }
  const FootContactQuality before = measure_foot_contact_quality(input, clip);
  CrowdAnimation kept = clip;
  keep_planted_feet_planted(input, 30, CorrectorParams{}, kept);
  const FootContactQuality after = measure_foot_contact_quality(input, kept);
  INFO("stance drift max: clip " << before.stance_drift_max_m << " m, kept " << after.stance_drift_max_m);
  CHECK(before.stance_drift_max_m > 0.01);
  CHECK(after.stance_drift_max_m < 0.001);
  CHECK(after.foot_pops == 0);
  // The left foot stands where the clip had it on frame 44; the right foot, planted all along, and the
  // frames before the window are the clip's.
  const auto end = joint_positions(c.shape, kept.characters[0].frames.back());
  const auto landed = joint_positions(c.shape, c.frames[44]);
  CHECK((end[left] - landed[left]).norm() < 1e-3);
  CHECK((end[right] - joint_positions(c.shape, c.frames.back())[right]).norm() < 1e-6);
  CHECK(kept.characters[0].frames[29].root_position_m == c.frames[29].root_position_m);
}

}  // namespace test_loop_closure
