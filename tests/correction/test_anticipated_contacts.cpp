// Anticipated contacts (issue 27, session 13; framework/correction/anticipate_contacts.hpp): a forearm
// that the input swings fast into a neighbour starts to turn away from its input before the contact, so
// its deviation never jumps by more than 20 deg within 3 frames (no flip), and the contact stays resolved.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/correction/anticipate_contacts.hpp"
#include "framework/correction/correct_crowd.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_anticipated_contacts {

using namespace crowdlab;

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

/// Turn angle (deg) of a rotation, q and -q alike.
double turn_deg(const Quat& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w())) / kDegToRad;
}

/// Two T-posed bodies. The first holds its right upper arm sideways and swings its right forearm
/// forward about the vertical at 25 deg per frame (frames 12-16, 0 to 100 deg), holds it, and swings it
/// back at 8 deg per frame from frame 30. The second stands in front of the first one's right elbow,
/// 24 cm away, arms down: the forearm runs into its back halfway through the swing. (A swing back as fast
/// as the swing in makes the engaged elbow lag its target, and the next run lags again on top of the
/// ramped lag: docs/correction.md, session 13.)
CrowdAnimation forearm_swung_into_a_neighbour_at_25_deg_per_frame() {
  const BodyShape body = make_procedural_body({});
  const Pose rest = Pose::rest(body);
  const Vec3 elbow = world_capsules(body, rest)[kRightElbow].a;
  Pose neighbour = rest;
  neighbour.root_position_m += Vec3(elbow.x(), 0.0, 0.20);
  neighbour.local_rotations[kLeftShoulder] = Quat(Eigen::AngleAxisd(-80.0 * kDegToRad, Vec3::UnitZ()));
  neighbour.local_rotations[kRightShoulder] = Quat(Eigen::AngleAxisd(80.0 * kDegToRad, Vec3::UnitZ()));
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.characters.resize(2);
  crowd.characters[0].name = "swinger";
  crowd.characters[1].name = "neighbour";
  for (CharacterAnimation& c : crowd.characters) c.shape = body;
  for (int f = 0; f < 60; ++f) {
    const double swing_deg = std::clamp(25.0 * (f - 12), 0.0, 100.0) - std::clamp(8.0 * (f - 30), 0.0, 100.0);
    Pose swinger = rest;
    // The right forearm points along -x in the T-pose; a positive turn about +y brings it forward (+z).
    swinger.local_rotations[kRightElbow] = Quat(Eigen::AngleAxisd(swing_deg * kDegToRad, Vec3::UnitY()));
    crowd.characters[0].frames.push_back(swinger);
    crowd.characters[1].frames.push_back(neighbour);
  }
  return crowd;
}

/// Deepest inter-body penetration (m) over every frame.
double deepest_over_clip(const CrowdAnimation& crowd) {
  double deepest = 0.0;
  for (int f = 0; f < crowd.frame_count(); ++f) {
    std::vector<WorldCapsules> bodies;
    for (const CharacterAnimation& c : crowd.characters)
      bodies.push_back(world_capsules(c.shape, c.frames[static_cast<size_t>(f)]));
    deepest = std::max(deepest, deepest_crowd_penetration(bodies));
  }
  return deepest;
}

/// Flips of the swinging crowd and its deepest inter-body penetration (m), corrected with `params`.
struct SwingResult {
  JointFlips flips;
  double deepest_m = 0.0;
};

SwingResult correct_the_swing(const CrowdAnimation& input, const CorrectorParams& params) {
  const CrowdAnimation out = correct_crowd(input, params);
  return {measure_joint_flips(input, out), deepest_over_clip(out)};
}

}  // namespace

TEST_CASE(
    "correction: a forearm swung into a neighbour at 25 deg per frame does not flip: engaged elbows are "
    "rate-limited",
    "[correction][anticipation]") {
  // Sessions 11-12: the step stopped such a forearm within a frame of the contact, so its deviation grew
  // by the input's 25 deg per frame (stationary crowds at 6.66 /m^2: ~210 elbow flips in 3 s). With the
  // elbow limit off (elbows out of rate_limited_joints, as in session 12) this clip flips; on, the elbow
  // turns at most 6.5 deg per frame and the shoulder, the trunk and the neighbour give way instead.
  const CrowdAnimation input = forearm_swung_into_a_neighbour_at_25_deg_per_frame();
  REQUIRE(deepest_over_clip(input) > 0.05);  // the input goes deep into the neighbour
  CorrectorParams params;
  params.rate_limited_joints &= ~kElbowJoints;
  const SwingResult unlimited = correct_the_swing(input, params);
  INFO("elbows unlimited: " << unlimited.flips.count << " flips, largest change "
                            << unlimited.flips.max_change_deg << " deg, deepest " << unlimited.deepest_m
                            << " m");
  CHECK(unlimited.flips.count > 0);  // the mechanism this removes is there
  const SwingResult limited = correct_the_swing(input, CorrectorParams{});
  INFO("elbows limited (default): " << limited.flips.count << " flips, largest change "
                                    << limited.flips.max_change_deg << " deg, deepest " << limited.deepest_m
                                    << " m");
  CHECK(limited.flips.count == 0);
  CHECK(limited.deepest_m <= std::max(0.01, unlimited.deepest_m + 0.002));
}

TEST_CASE("correction: a forearm swung into a neighbour is anticipated by a second run: no flip, shallow",
          "[correction][anticipation]") {
  // The opt-in alternative (anticipated_joints; not the default, docs/correction.md session 13): with the
  // elbow limit off, the second run's target already turns the forearm away before the contact.
  const CrowdAnimation input = forearm_swung_into_a_neighbour_at_25_deg_per_frame();
  CorrectorParams params;
  params.rate_limited_joints &= ~kElbowJoints;
  const SwingResult causal = correct_the_swing(input, params);
  params.anticipated_joints = "arms";
  const SwingResult anticipated = correct_the_swing(input, params);
  INFO("one run: " << causal.flips.count << " flips; anticipated: " << anticipated.flips.count
                   << " flips, largest change " << anticipated.flips.max_change_deg << " deg, deepest "
                   << anticipated.deepest_m << " m");
  CHECK(causal.flips.count > 0);
  CHECK(anticipated.flips.count == 0);
  CHECK(anticipated.deepest_m <= std::max(0.01, causal.deepest_m + 0.002));
}

TEST_CASE(
    "correction: a contact deviation is ramped up before and down after at the given rate, kept at "
    "its peak",
    "[correction][anticipation]") {
  // A deviation that jumps to 60 deg on frames 20-29 and back to none: ramped at 5 deg per frame over the
  // 12 frames before and after, 60 deg where the run had them; no frame turns by more than 5 deg.
  std::vector<Quat> deviation(50, Quat::Identity());
  for (size_t f = 20; f < 30; ++f) deviation[f] = Quat(Eigen::AngleAxisd(60.0 * kDegToRad, Vec3::UnitX()));
  const std::vector<Quat> ramp = ramp_deviations(deviation, 5.0 * kDegToRad, false);
  REQUIRE(ramp.size() == deviation.size());
  CHECK(turn_deg(ramp[5]) == Approx(0.0).margin(1e-9));
  CHECK(turn_deg(ramp[14]) == Approx(30.0).margin(1e-6));
  CHECK(turn_deg(ramp[25]) == Approx(60.0).margin(1e-6));
  CHECK(turn_deg(ramp[35]) == Approx(30.0).margin(1e-6));
  CHECK(turn_deg(ramp[45]) == Approx(0.0).margin(1e-9));
  for (size_t f = 1; f < ramp.size(); ++f) CHECK(turn_deg(ramp[f - 1].conjugate() * ramp[f]) <= 5.0 + 1e-9);
  // Around a loop's seam: a deviation on the first frames is ramped up on the last ones.
  std::vector<Quat> at_start(50, Quat::Identity());
  for (size_t f = 0; f < 5; ++f) at_start[f] = deviation[25];
  CHECK(turn_deg(ramp_deviations(at_start, 5.0 * kDegToRad, true)[49]) == Approx(55.0).margin(1e-6));
  CHECK(turn_deg(ramp_deviations(at_start, 5.0 * kDegToRad, false)[49]) == Approx(0.0).margin(1e-9));
  CHECK_THROWS_AS(anticipated_joint_set("hands"), InputError);
}

}  // namespace test_anticipated_contacts
