// The input a walking crowd's second correction follows (follow_root_offsets.hpp; issue 27, session 27):
// roots moved by the first correction's smoothed offsets, footprints moved rigidly, nothing else.
#include <catch2/catch.hpp>

#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/follow_root_offsets.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "tests/correction/corridor_walkers.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_follow_root_offsets {

using namespace crowdlab;

namespace {

Vec3 ankle_at(const CharacterAnimation& ch, size_t f, int ankle) {
  return forward_kinematics(ch.shape, ch.frames[f])[static_cast<size_t>(ankle)].translation;
}

/// Per frame, whether the input plants the foot of `leg` (ankle or ball), by the holds' test.
std::vector<bool> planted(const CharacterAnimation& ch, const LegJoints& leg, double fps) {
  const FollowRootDef def;
  std::vector<bool> out(ch.frames.size(), false);
  for (size_t f = 1; f < ch.frames.size(); ++f) {
    const BoneTransforms a = forward_kinematics(ch.shape, ch.frames[f - 1]);
    const BoneTransforms b = forward_kinematics(ch.shape, ch.frames[f]);
    for (int j : {leg.ankle, leg.foot}) {
      const auto jj = static_cast<size_t>(j);
      if ((b[jj].translation - a[jj].translation).norm() < def.foot_plant_speed_mps / fps &&
          b[jj].translation.y() < def.foot_plant_height_m)
        out[f] = true;
    }
  }
  return out;
}

}  // namespace

TEST_CASE(
    "follow root offsets: roots take the smoothed offsets, planted feet move as one footprint, the "
    "unmoved characters stay exactly",
    "[correction]") {
  const CrowdAnimation input = test::corridor_walkers(2.0, false, false, 2.0);
  REQUIRE(input.characters.size() >= 3);
  const int frames = input.frame_count();
  const double fps = input.meta.fps;
  // A made-up first correction: character 0 stands 10 cm to the side on every frame, character 1 is
  // pushed back steadily (0 -> 20 cm over the clip, also through its stances), the others are not moved.
  CrowdAnimation corrected = input;
  const Vec3 side(0.1, 0.0, 0.0);
  auto ramp = [&](int f) { return Vec3(0.0, 0.0, -0.2 * f / (frames - 1)); };
  for (int f = 0; f < frames; ++f) {
    corrected.characters[0].frames[static_cast<size_t>(f)].root_position_m += side;
    corrected.characters[1].frames[static_cast<size_t>(f)].root_position_m += ramp(f) + Vec3(0, 0.05, 0);
  }
  const CrowdAnimation replanned = follow_root_offsets(input, corrected, FollowRootDef{});
  REQUIRE(replanned.characters.size() == input.characters.size());

  // Unmoved characters are returned bit for bit.
  for (size_t c = 2; c < input.characters.size(); ++c)
    for (int f = 0; f < frames; ++f) {
      const Pose& a = input.characters[c].frames[static_cast<size_t>(f)];
      const Pose& b = replanned.characters[c].frames[static_cast<size_t>(f)];
      REQUIRE(a.root_position_m == b.root_position_m);
      for (int j = 0; j < kJointCount; ++j)
        REQUIRE(a.local_rotations[static_cast<size_t>(j)].coeffs() ==
                b.local_rotations[static_cast<size_t>(j)].coeffs());
    }

  // A constant offset moves the whole walker: its root and both ankles by exactly that offset.
  for (int f = 0; f < frames; ++f) {
    const auto ff = static_cast<size_t>(f);
    CHECK((replanned.characters[0].frames[ff].root_position_m -
           input.characters[0].frames[ff].root_position_m - side)
              .norm() < 1e-12);
    for (LegSide side_of_leg : kLegSides) {
      const int ankle = leg_joints(side_of_leg).ankle;
      CHECK((ankle_at(replanned.characters[0], ff, ankle) - ankle_at(input.characters[0], ff, ankle) - side)
                .norm() < 1e-6);
    }
  }

  // A push that grows through the stances: the root follows it horizontally (the first correction's
  // height change is not followed; a Gaussian keeps a straight ramp away from the clip's ends), and each
  // planted stretch of the input's foot moves as one footprint, so the re-planned input does not skate.
  const CharacterAnimation& in1 = input.characters[1];
  const CharacterAnimation& re1 = replanned.characters[1];
  const int reach = static_cast<int>(std::ceil(3.0 * FollowRootDef{}.smoothing_s * fps));
  for (int f = reach; f < frames - reach; ++f) {
    const auto ff = static_cast<size_t>(f);
    CHECK((re1.frames[ff].root_position_m - in1.frames[ff].root_position_m - ramp(f)).norm() < 1e-9);
  }
  int stance_frames = 0;
  for (LegSide side_of_leg : kLegSides) {
    const LegJoints leg = leg_joints(side_of_leg);
    const std::vector<bool> down = planted(in1, leg, fps);
    for (int f = 1; f < frames; ++f) {
      if (!down[static_cast<size_t>(f)] || !down[static_cast<size_t>(f - 1)]) continue;
      ++stance_frames;
      const Vec3 moved_now =
          ankle_at(re1, static_cast<size_t>(f), leg.ankle) - ankle_at(in1, static_cast<size_t>(f), leg.ankle);
      const Vec3 moved_before = ankle_at(re1, static_cast<size_t>(f - 1), leg.ankle) -
                                ankle_at(in1, static_cast<size_t>(f - 1), leg.ankle);
      CHECK((moved_now - moved_before).norm() < 1e-6);
    }
  }
  CHECK(stance_frames > frames / 2);  // the walker does plant its feet
}

TEST_CASE(
    "follow root offsets: the dense corridor corrected twice follows its pushed roots with fewer "
    "flips and less float, and no more than twice the steps",
    "[correction]") {
  const CrowdAnimation input = test::corridor_walkers(test::kSanitized ? 1.0 : 3.0, true, false, 3.0);
  CorrectorParams once;
  CorrectorParams twice;
  twice.follow_root_smoothing_s = 0.3;
  CHECK(follows_root_offsets(input, twice));
  CHECK_FALSE(follows_root_offsets(input, once));
  CHECK(correction_steps(input, twice) == 2 * correction_steps(input, once));
  const CorrectionQuality q1 = measure_correction_quality(input, correct_crowd(input, once), 0, 1, false);
  const CorrectionQuality q2 = measure_correction_quality(input, correct_crowd(input, twice), 0, 1, false);
  INFO("flips " << q1.flips.count << " -> " << q2.flips.count << ", float p99 mm "
                << 1e3 * q1.feet.float_p99_m << " -> " << 1e3 * q2.feet.float_p99_m << ", depth p99 mm "
                << 1e3 * q1.depth_p99_m << " -> " << 1e3 * q2.depth_p99_m << ", mean deviation deg "
                << q1.rotation_dev_mean_deg << " -> " << q2.rotation_dev_mean_deg << ", free-limb max deg "
                << q1.free_limbs.max_deg << " -> " << q2.free_limbs.max_deg);
  CHECK(q2.flips.count <= q1.flips.count);
  CHECK(q2.feet.float_p99_m <= q1.feet.float_p99_m);
  CHECK(q2.rotation_dev_mean_deg < q1.rotation_dev_mean_deg);
  CHECK(q2.depth_p99_m <= q1.depth_p99_m + 0.001);
  CHECK(q2.free_limbs.max_deg <= 5.0);
}

TEST_CASE("follow root offsets: a clip corrected into a loop is corrected once", "[correction]") {
  CrowdAnimation input = test::corridor_walkers(1.0, false, false, 2.0);
  // The walkers made to come back to where they started, as a looping clip does.
  for (CharacterAnimation& ch : input.characters) ch.frames.back() = ch.frames.front();
  CorrectorParams p;
  p.follow_root_smoothing_s = 0.3;
  p.loop_preroll_s = 0.5;
  CHECK_FALSE(follows_root_offsets(input, p));
  p.loop_preroll_s = 0.0;
  CHECK(follows_root_offsets(input, p));
  p.follow_root_smoothing_s = -0.1;
  CHECK_THROWS_AS(correct_crowd(input, p), InputError);
}

}  // namespace test_follow_root_offsets
