// loop_seam_per_character (issue 28, session 14): the last-to-first step of a looping clip split by
// character and body part, to find which characters carry a seam.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/loop_seam_per_character.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_loop_seam_per_character {

using namespace crowdlab;

TEST_CASE("loop seam per character finds the character whose arm jumps at the seam", "[core][loop]") {
  SwayingCrowdOptions o;
  o.characters = 6;
  o.frames = 40;
  CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  // Every character's last frame is its frame 1, so stepping back to frame 0 is an ordinary step...
  for (CharacterAnimation& c : crowd.characters) c.frames.back() = c.frames[1];
  // ...but character 2's left arm is raised by 30 degrees on the last frame: a seam at its arm only.
  Pose& last = crowd.characters[2].frames.back();
  last.local_rotations[kLeftShoulder] =
      Quat(Eigen::AngleAxisd(30.0 * std::numbers::pi / 180.0, Vec3::UnitZ())) *
      last.local_rotations[kLeftShoulder];
  const std::vector<CharacterSeam> seams = loop_seam_per_character(crowd);
  REQUIRE(seams.size() == crowd.characters.size());
  for (size_t c = 0; c < seams.size(); ++c) {
    const CharacterAnimation& ch = crowd.characters[c];
    INFO("character " << c << ": seam " << seams[c].seam_m << " m, median step " << seams[c].median_step_m
                      << " m, arms " << seams[c].arms_m << ", legs " << seams[c].legs_m << ", trunk "
                      << seams[c].trunk_m);
    CHECK(seams[c].median_step_m > 0.0);
    CHECK(seams[c].legs_m < 1e-12);  // the fixture's legs stand still
    if (c == 2) continue;
    const auto a = joint_positions(ch.shape, ch.frames[1]), b = joint_positions(ch.shape, ch.frames[0]);
    double step = 0.0;
    for (size_t j = 0; j < a.size(); ++j) step += (a[j] - b[j]).norm();
    CHECK(seams[c].seam_m == Approx(step / static_cast<double>(a.size())).epsilon(1e-12));
    CHECK(seams[c].arms_m < 0.1 * seams[2].arms_m);
    CHECK(seams[c].excess_m() < seams[2].excess_m());
  }
  // The raised arm moves the left elbow, wrist and hand (3 of the 10 arm joints) by tens of centimetres.
  CHECK(seams[2].arms_m > 0.03);
  CHECK(loop_seam_per_character(CrowdAnimation{}).empty());
}

}  // namespace test_loop_seam_per_character
