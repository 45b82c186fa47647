// Feet below the input's ground (issue 27, session 17): with params.feet_above_input_ground, hold_feet lifts
// a foot whose sole the correction put more than 5 mm below min(0, the input's sole) back to 5 mm below it
// by the leg IK, held or swinging, and leaves alone what the input itself puts below y = 0.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>

#include "framework/core/body_shape.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/corrector_step.hpp"
#include "tests/correction/held_stand.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_feet_above_ground {

using namespace crowdlab;

/// One body standing still, its lower sole input_sole_m above y = 0 in the input, its feet held; the lift
/// on or off, and the settle onto the held feet's input height (held_feet_at_input_height) off unless asked
/// for, whatever the defaults: it too raises a sunk body, which would hide what the lift does.
test::HeldStand stand(bool lift_feet, double input_sole_m, bool settle = false) {
  CorrectorParams params;
  params.feet_above_input_ground = lift_feet;
  params.held_feet_at_input_height = settle;
  return test::stand_with_held_feet(params, input_sole_m);
}

/// How deep below the input's ground the lift leaves a foot (stage_foot_holds.cpp, kBelowGroundAllowed_m).
constexpr double kAllowed_m = 0.005;

/// Both soles (m) of `pose`.
std::array<double, 2> soles_m(const BodyShape& shape, const Pose& pose) {
  const WorldCapsules caps = world_capsules(shape, pose);
  return {foot_sole_height_m(caps, leg_joints(LegSide::kLeft)),
          foot_sole_height_m(caps, leg_joints(LegSide::kRight))};
}

/// The soles after hold_feet on the last output with its body lowered by drop_m (held: the feet as the
/// corrector holds them, else both swinging).
std::array<double, 2> soles_after_hold_feet(bool lift_feet, double input_sole_m, double drop_m, bool held) {
  test::HeldStand h = stand(lift_feet, input_sole_m);
  REQUIRE(h.state.foot_holds[0].held());
  REQUIRE(h.state.foot_holds[1].held());
  if (!held) h.state.foot_holds.assign(2, FootHold{});
  Pose pose = h.state.output[0];
  pose.root_position_m.y() -= drop_m;
  hold_feet(h.model, h.state, 0, pose);
  return soles_m(h.shape, pose);
}

TEST_CASE("correction: feet the correction puts below the ground are lifted back to 5 mm below it",
          "[correction]") {
  // Session 16-17 traced the corridor's feet below the ground to bodies standing 7-22 mm lower than the
  // input's: the leg, posed as the input's, ends below y = 0 (co666: 28-41 mm below the input's ground).
  for (bool held : {true, false}) {
    const auto lifted = soles_after_hold_feet(true, 0.0, 0.015, held);
    const auto left = soles_after_hold_feet(false, 0.0, 0.015, held);
    INFO((held ? "held" : "swinging") << " feet: soles " << lifted[0] << ", " << lifted[1] << " m lifted; "
                                      << left[0] << ", " << left[1] << " m not");
    for (double y : lifted) CHECK(y == Approx(-kAllowed_m).margin(1e-5));  // lifted, not raised
    for (double y : left) CHECK(y < -0.010);                               // without the lift the drop stays
  }
}

TEST_CASE("correction: feet the input itself puts below the ground are lifted only to the input's sole",
          "[correction]") {
  // The measure foot_ground_penetration_added counts depth below min(0, the input's sole): an input foot
  // 14 mm below y = 0 is the input's, and a lift to y = 0 would move the foot 14 mm off the input.
  const auto soles = soles_after_hold_feet(true, -0.014, 0.012, true);
  INFO("soles " << soles[0] << ", " << soles[1] << " m; the input's -0.014 m, lowered to -0.026 m");
  for (double y : soles) CHECK(y == Approx(-0.014 - kAllowed_m).margin(1e-5));
}

TEST_CASE("correction: a corrector step keeps a lowered body's feet on the input's ground", "[correction]") {
  // The whole step (solve, projection, hold_feet, pass, settle), from a state whose body sank 2 cm: the
  // solve's ground springs alone leave the feet more than 5 mm below the ground. Each option is set
  // explicitly: the lift alone, neither, and both (the lift and the settle, variant D5s: session 18).
  const auto soles_after_step = [](test::HeldStand h) {
    Pose sunk = h.state.output[0];
    sunk.root_position_m.y() -= 0.02;
    set_bones_from_pose(h.model, 0, sunk, h.state.com_m, h.state.rotation);
    return soles_m(h.shape, corrector_step(h.model, h.state, {h.stand})[0]);
  };
  const auto lifted = soles_after_step(stand(true, 0.0)), left = soles_after_step(stand(false, 0.0));
  const auto both = soles_after_step(stand(true, 0.0, true));
  INFO("soles after the step " << lifted[0] << ", " << lifted[1] << " m lifted; " << left[0] << ", "
                               << left[1] << " m not; " << both[0] << ", " << both[1]
                               << " m with the settle too");
  const double tol = CorrectorParams{}.foot_hold_tolerance_m;
  for (double y : lifted) CHECK(y >= -kAllowed_m - tol);
  for (double y : both) CHECK(y >= -kAllowed_m - tol);
  CHECK(std::min(left[0], left[1]) < -kAllowed_m - tol);
}

}  // namespace test_feet_above_ground
