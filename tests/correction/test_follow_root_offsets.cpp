// The input a walking crowd's second correction follows (follow_root_offsets.hpp; issue 27, session 27):
// roots moved by the first correction's smoothed offsets, footprints moved rigidly, nothing else.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

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
  const CorrectorParams def;
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
  const FollowRootDef def;
  const CrowdAnimation replanned = follow_root_offsets(input, corrected, def, CorrectorParams{});
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

  // A constant offset moves the whole walker: its root and both ankles by exactly its followed share.
  for (int f = 0; f < frames; ++f) {
    const auto ff = static_cast<size_t>(f);
    CHECK((replanned.characters[0].frames[ff].root_position_m -
           input.characters[0].frames[ff].root_position_m - def.share * side)
              .norm() < 1e-12);
    for (LegSide side_of_leg : kLegSides) {
      const int ankle = leg_joints(side_of_leg).ankle;
      CHECK((ankle_at(replanned.characters[0], ff, ankle) - ankle_at(input.characters[0], ff, ankle) -
             def.share * side)
                .norm() < 1e-6);
    }
  }

  // A push that grows through the stances: the root follows its share horizontally (the first correction's
  // height change is not followed; a Gaussian keeps a straight ramp away from the clip's ends), and each
  // planted stretch of the input's foot moves as one footprint, so the re-planned input does not skate.
  const CharacterAnimation& in1 = input.characters[1];
  const CharacterAnimation& re1 = replanned.characters[1];
  const int reach = static_cast<int>(std::ceil(3.0 * def.smoothing_s * fps));
  for (int f = reach; f < frames - reach; ++f) {
    const auto ff = static_cast<size_t>(f);
    CHECK((re1.frames[ff].root_position_m - in1.frames[ff].root_position_m - def.share * ramp(f)).norm() <
          1e-9);
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
    "flips and less float, in twice the steps",
    "[correction]") {
  // The corridor is chaotic (a 0.1 % change of the stiffness moves the flips by a quarter), so the claim is
  // on three runs together, the stiffness at 119.9 / 120 / 120.1 (docs/correction.md, session 27).
  const CrowdAnimation input = test::corridor_walkers(test::kSanitized ? 1.0 : 3.0, true, false, 3.0);
  CorrectorParams once;
  CorrectorParams twice;
  twice.follow_root_smoothing_s = 0.3;
  CHECK(follows_root_offsets(input, twice));
  CHECK_FALSE(follows_root_offsets(input, once));
  CHECK(correction_steps(input, twice) == 2 * correction_steps(input, once));
  struct Sum {
    long flips = 0;
    double float_m = 0.0, depth_m = 0.0, mean_deg = 0.0, free_limb_max_deg = 0.0;
  };
  auto measure = [&](const CorrectorParams& p, Sum& sum) {
    const CorrectionQuality q = measure_correction_quality(input, correct_crowd(input, p), 0, 1, false);
    sum.flips += q.flips.count;
    sum.float_m += q.feet.float_p99_m;
    sum.depth_m += q.depth_p99_m;
    sum.mean_deg += q.rotation_dev_mean_deg;
    sum.free_limb_max_deg = std::max(sum.free_limb_max_deg, q.free_limbs.max_deg);
  };
  Sum s1, s2;
  // Under the sanitizers (about 20 times slower) one short run looks for memory errors; Release checks.
  for (const double k :
       test::kSanitized ? std::vector<double>{120.0} : std::vector<double>{119.9, 120.0, 120.1}) {
    once.stiffness = twice.stiffness = k;
    measure(once, s1);
    measure(twice, s2);
  }
  INFO("three runs: flips " << s1.flips << " -> " << s2.flips << ", float p99 mm " << 1e3 * s1.float_m
                            << " -> " << 1e3 * s2.float_m << ", depth p99 mm " << 1e3 * s1.depth_m << " -> "
                            << 1e3 * s2.depth_m << ", mean deviation deg " << s1.mean_deg << " -> "
                            << s2.mean_deg << ", free-limb max deg " << s1.free_limb_max_deg << " -> "
                            << s2.free_limb_max_deg);
  CHECK(s2.free_limb_max_deg <= 5.0);
  if (test::kSanitized) return;
  CHECK(s2.flips < s1.flips);
  CHECK(s2.float_m < s1.float_m);
  CHECK(s2.mean_deg < s1.mean_deg);
  CHECK(s2.depth_m <= 1.1 * s1.depth_m);
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
