// Free-limb deviation, joint flips and environment penetration (issue 27;
// framework/metrics/free_limb_deviation.hpp, core/joint_flips.hpp, metrics/environment_penetration.hpp) on
// hand-made animations whose answers are known.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/capsule_box_distance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/environment_penetration.hpp"
#include "framework/metrics/free_limb_deviation.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_free_limb_measures {

using namespace crowdlab;

namespace {

constexpr int kFrames = 60;  // 2 s at 30 fps

Quat about_x(double deg) {
  return Quat(Eigen::AngleAxisd(deg * std::numbers::pi / 180.0, Vec3::UnitX()));
}

/// Characters standing still in the rest pose at the given x positions (m), 2 s.
CrowdAnimation standing(const std::vector<double>& xs) {
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  for (size_t i = 0; i < xs.size(); ++i) {
    CharacterAnimation c;
    c.name = "c" + std::to_string(i);
    c.shape = make_procedural_body({Sex::kFemale, 1.65, 1.0});
    for (int f = 0; f < kFrames; ++f) {
      Pose p = Pose::rest(c.shape);
      p.root_position_m = Vec3(xs[i], c.shape.pelvis_height_m(), 0.0);
      c.frames.push_back(p);
    }
    crowd.characters.push_back(c);
  }
  return crowd;
}

}  // namespace

TEST_CASE("a turned wrist of a character alone is a free-limb deviation, one touching a neighbour is not") {
  const CrowdAnimation in = standing({0.0, 3.0});
  CrowdAnimation out = in;
  for (Pose& p : out.characters[0].frames)
    p.local_rotations[kLeftWrist] = about_x(4.0) * p.local_rotations[kLeftWrist];
  FreeLimbDeviation q = measure_free_limb_deviation(in, out);
  CHECK(q.max_deg == Approx(4.0).epsilon(1e-6));
  CHECK(q.p99_deg == Approx(4.0).epsilon(1e-6));
  CHECK(q.worst_character == 0);
  CHECK(q.worst_joint == kLeftWrist);
  CHECK(q.free_joint_frames == 2 * 24 * kFrames);  // everybody is free all the time

  // The same change with a neighbour 0.5 m away (arms within 10 cm of each other): not free.
  const CrowdAnimation close_in = standing({0.0, 0.5});
  CrowdAnimation close_out = close_in;
  for (Pose& p : close_out.characters[0].frames)
    p.local_rotations[kLeftWrist] = about_x(4.0) * p.local_rotations[kLeftWrist];
  q = measure_free_limb_deviation(close_in, close_out);
  CHECK(q.max_deg == 0.0);
  CHECK(q.free_joint_frames < 2 * 24 * kFrames);
  CHECK(q.worst_character == -1);
}

TEST_CASE("a limb near something within half a second is not free, farther in time it is") {
  // Character 1 stands 0.5 m away on frames 20..24 only (elsewhere 3 m away), so character 0's wrist is
  // busy on frames 20..24 and not free on 5..39 (+-15 frames at 30 fps).
  CrowdAnimation in = standing({0.0, 3.0});
  for (int f = 20; f < 25; ++f) in.characters[1].frames[static_cast<size_t>(f)].root_position_m.x() = 0.5;
  auto deviate_on = [&](int first, int last) {
    CrowdAnimation out = in;
    for (int f = first; f <= last; ++f) {
      Quat& r = out.characters[0].frames[static_cast<size_t>(f)].local_rotations[kLeftWrist];
      r = about_x(3.0) * r;
    }
    return measure_free_limb_deviation(in, out);
  };
  CHECK(deviate_on(5, 39).max_deg == 0.0);  // only where it is not free
  const FreeLimbDeviation q = deviate_on(4, 39);
  CHECK(q.max_deg == Approx(3.0).epsilon(1e-6));
  CHECK(q.worst_frame == 4);
  CHECK(deviate_on(40, 40).worst_frame == 40);
}

TEST_CASE("a looping clip's free-limb window wraps around the loop: its last frames are near its first") {
  // Character 1 stands 0.5 m away on the clip's last 5 frames only: character 0's wrist is busy on frames
  // 55..59. Played once, frame 0 is 55 frames from them; played as a loop, it follows frame 59.
  CrowdAnimation in = standing({0.0, 3.0});
  for (int f = kFrames - 5; f < kFrames; ++f)
    in.characters[1].frames[static_cast<size_t>(f)].root_position_m.x() = 0.5;
  CrowdAnimation out = in;
  for (int f = 0; f <= 15; ++f) {  // the wrist turned on frames 0..15, as a loop's closure might leave it
    Quat& r = out.characters[0].frames[static_cast<size_t>(f)].local_rotations[kLeftWrist];
    r = about_x(6.0) * r;
  }
  const FreeLimbDeviation once = measure_free_limb_deviation(in, out);
  CHECK(once.max_deg == Approx(6.0).epsilon(1e-6));
  CHECK(once.worst_frame == 0);
  const FreeLimbDeviation looped = measure_free_limb_deviation(in, out, 0, true);
  CHECK(looped.max_deg == Approx(6.0).epsilon(1e-6));  // frame 15 is 16 frames after frame 59
  CHECK(looped.worst_frame == 15);
  CHECK(looped.free_joint_frames < once.free_joint_frames);
  // Frames 0..14 are within 15 frames (0.5 s) of frame 59 around the loop: turned only there, no free limb.
  CrowdAnimation early = in;
  for (int f = 0; f <= 14; ++f) {
    Quat& r = early.characters[0].frames[static_cast<size_t>(f)].local_rotations[kLeftWrist];
    r = about_x(6.0) * r;
  }
  CHECK(measure_free_limb_deviation(in, early, 0, true).max_deg == 0.0);
  CHECK(measure_free_limb_deviation(in, early).max_deg == Approx(6.0).epsilon(1e-6));
  // correction_quality passes `looped` on.
  CHECK(measure_free_limb_deviation(in, in, 0, true).free_joint_frames ==
        measure_correction_quality(in, in, 0, 1, false, true).free_limbs.free_joint_frames);
}

TEST_CASE("a wrist that turns 30 deg away from its input within two frames is a flip, a slow turn is not") {
  const CrowdAnimation in = standing({0.0});
  CrowdAnimation fast = in, slow = in;
  for (int f = 0; f < kFrames; ++f) {
    const double jump = f >= 30 ? 30.0 : (f == 29 ? 15.0 : 0.0);  // 0 -> 15 -> 30 deg over frames 28-30
    fast.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist] =
        in.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist] * about_x(jump);
    slow.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist] =
        in.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist] * about_x(0.5 * f);
  }
  const JointFlips q = measure_joint_flips(in, fast);
  // Frames 30 and 31 see 30 deg against frames 27-28 (frame 32 only 15 deg against frame 29).
  CHECK(q.count == 2);
  REQUIRE(q.first.size() == 2);
  CHECK(q.first[0].character == 0);
  CHECK(q.first[0].joint == kRightWrist);
  CHECK(q.first[0].frame == 30);
  CHECK(q.max_change_deg == Approx(30.0).epsilon(1e-6));
  const JointFlips s = measure_joint_flips(in, slow);
  CHECK(s.count == 0);
  CHECK(s.max_change_deg == Approx(1.5).epsilon(1e-6));
  // A copy with every quaternion negated is the same rotation: no flip, no deviation.
  CrowdAnimation negated = in;
  for (Pose& p : negated.characters[0].frames)
    for (Quat& r : p.local_rotations) r.coeffs() = -r.coeffs();
  CHECK(measure_joint_flips(in, negated).count == 0);
  CHECK(measure_free_limb_deviation(in, negated).max_deg == Approx(0.0).margin(1e-6));
}

TEST_CASE("a looping clip that jumps back at its seam has flips there, and played once none") {
  // The wrist's deviation rises slowly (1 deg a frame) from frame 20 to 30 deg at frame 50 and stays: no
  // flip within the clip. Around the loop frame 0 (deviation 0) follows frame 59 (30 deg): frames 0, 1
  // and 2 see that 30 deg jump within their 3-frame window.
  const CrowdAnimation in = standing({0.0});
  CrowdAnimation out = in;
  for (int f = 0; f < kFrames; ++f) {
    const double deg = std::clamp(static_cast<double>(f - 20), 0.0, 30.0);
    Quat& r = out.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist];
    r = r * about_x(deg);
  }
  CHECK(measure_joint_flips(in, out).count == 0);
  const JointFlips looped = measure_joint_flips(in, out, 0, true);
  CHECK(looped.count == 3);
  REQUIRE(looped.first.size() == 3);
  CHECK(looped.first[0].frame == 0);
  CHECK(looped.first[2].frame == 2);
  CHECK(looped.max_change_deg == Approx(30.0).epsilon(1e-6));
  CHECK(measure_correction_quality(in, out, 0, 1, false, true).flips.count == 3);
  CHECK(measure_correction_quality(in, out, 0, 1, false, false).flips.count == 0);
}

TEST_CASE("the flip threshold is a rate over 0.1 s, so a clip's frame rate does not change what a flip is") {
  CHECK(flip_window(30.0).frames == 3);
  CHECK(flip_window(30.0).angle_deg == Approx(20.0));
  CHECK(flip_window(60.0).frames == 6);
  CHECK(flip_window(60.0).angle_deg == Approx(20.0));
  CHECK(flip_window(15.0).frames == 2);
  CHECK(flip_window(15.0).angle_deg == Approx(200.0 * 2.0 / 15.0));
  CHECK(flip_window(5.0).frames == 1);  // never less than one frame
  CHECK_THROWS_AS(flip_window(0.0), InputError);
  CHECK_THROWS_AS(flip_window(std::nan("")), InputError);

  // The same two motions at 15 fps: a wrist returning at the corrector's release rate (3.4 rad/s, 13 deg
  // per frame, 39 deg within 3 frames) is no flip; a 40 deg turn within one frame (600 deg/s) is.
  CrowdAnimation in = standing({0.0});
  in.meta.fps = 15.0;
  CrowdAnimation returning = in, jumping = in;
  const double per_frame_deg = 3.4 / 15.0 * 180.0 / std::numbers::pi;
  for (int f = 0; f < kFrames; ++f) {
    Quat& r = returning.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist];
    r = r * about_x(std::max(0.0, 60.0 - per_frame_deg * f));
    Quat& j = jumping.characters[0].frames[static_cast<size_t>(f)].local_rotations[kRightWrist];
    j = j * about_x(f >= 30 ? 40.0 : 0.0);
  }
  CHECK(measure_joint_flips(in, returning).count == 0);
  CHECK(measure_joint_flips(in, jumping).count == 2);  // frames 30 and 31 see frame 29's deviation
}

TEST_CASE("capsule-box distance is exact, and environment penetration measures capsules behind a wall") {
  Box wall;
  wall.center_m = Vec3(1.0, 0.6, 0.0);
  wall.half_extents_m = Vec3(0.05, 0.6, 5.0);
  // A vertical capsule of radius 0.1 whose axis is 0.02 m from the wall's face x = 0.95: 8 cm inside.
  const Capsule c{Vec3(0.93, 0.3, 0.0), Vec3(0.93, 0.9, 0.0), 0.1};
  CHECK(capsule_box_distance(c, wall).distance_m == Approx(-0.08).epsilon(1e-9));
  // Tilted: only its top end comes near, 0.02 m from the face -> 8 cm inside at the end.
  const Capsule tilted{Vec3(0.5, 0.3, 0.0), Vec3(0.93, 0.9, 0.0), 0.1};
  const CapsuleBoxDistance t = capsule_box_distance(tilted, wall);
  CHECK(t.distance_m == Approx(-0.08).epsilon(1e-6));
  CHECK((t.axis_point - tilted.b).norm() < 1e-6);
  // Rotated box: same answer as the axis-aligned one turned with it.
  Box turned = wall;
  const Quat q(Eigen::AngleAxisd(0.7, Vec3::UnitY()));
  turned.rotation = q;
  turned.center_m = q * wall.center_m;
  const Capsule turned_c{q * c.a, q * c.b, c.radius_m};
  CHECK(capsule_box_distance(turned_c, turned).distance_m == Approx(-0.08).epsilon(1e-6));

  CrowdAnimation crowd = standing({0.0});
  CHECK(measure_environment_penetration(crowd).samples == 0);
  // A barrier through the character's body at x = 0: its pelvis capsule is inside.
  Box barrier;
  barrier.center_m = Vec3(0.0, 0.6, 0.0);
  barrier.half_extents_m = Vec3(0.05, 0.6, 2.0);
  crowd.environment.boxes.push_back(barrier);
  const EnvironmentPenetration e = measure_environment_penetration(crowd);
  CHECK(e.samples > 0);
  CHECK(e.max_m > 0.1);
  CHECK(e.worst_frame == 0);
  // Moved 1 m away: nothing inside.
  crowd.environment.boxes[0].center_m.x() = 1.0;
  CHECK(measure_environment_penetration(crowd).max_m == 0.0);
}

}  // namespace test_free_limb_measures
