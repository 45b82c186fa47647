// Settle held feet on the input's ground (ours; issue 27: planted feet floating and sinking in the
// corridor). Runs last in the step, after the depenetration pass and the release of free joints, on the
// characters the pass did not pose: those had their held feet's heights solved with their contacts
// there (session 13; session 12 settled every body here and the vertical moves undid separations).
//
// A held foot's height is held only softly: the solve's planted-foot spring pulls it toward the input's
// height (foot_goal), the leg IK of hold_feet keeps the solve's height (re-planting it held the legs too
// hard: docs/correction.md, sessions 8 and 10), and the pass's held-foot rows keep whatever height the
// step left. What the step leaves off that height stays for the whole stance. The pelvis carries the
// whole body, so the height error of the held feet is taken out by moving the root vertically, which
// bends no joint (no deviation, no flip) and moves every capsule of the body by the same small
// vertical amount:
//
//   e_s = y_s - y*_s            held foot s: its held joint's height minus its goal (foot_goal: the
//                               input's, approached at most at the foot motion budget per step)
//   one foot held:    Δy = -e_s
//   both held:        Δy = -e_s for the smaller |e_s| when both have the same sign (no foot is pushed
//                     past its goal), 0 when one floats and the other sinks (a leg-length question the
//                     pelvis cannot answer)
//   |Δy| <= foot_pop_budget_m per step (no foot jumps), and a lowered body keeps its swinging foot's
//   sole above min(0, its sole before) and its held feet's soles above min(-depenetration_tolerance_m,
//   their soles before): the settle never pushes a free foot into the ground, nor a held foot deeper than
//   the depenetration pass's ground guards let it go (the pass's tolerance). Without the held feet's
//   bound (session 18) the settle held a body whose input stands below the ground at the input's height
//   against the ground's push ("the ground pushes a sunken body up": a body sunk 3 cm with its input, foot
//   anchors off, rose 0 mm in 30 steps; with the bound 29 mm). The input's own feet below the
//   ground by less than the tolerance (the procedural stand's 3.5 mm) are still settled onto.
//
// The next step starts from the settled pose (velocities unchanged, as in the depenetration pass).
#include <algorithm>
#include <array>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
double held_height_error_m(const CorrectorModel& model, const CorrectorState& s, int c, int side,
                           const BoneTransforms& bones) {
  const FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
  const FootGoal goal = foot_goal(model, s, c, side);
  const LegJoints lj = leg_joints(kLegSides[side]);
  if (hold.ankle) return bones[static_cast<size_t>(lj.ankle)].translation.y() - goal.ankle_m.y();
  return bones[static_cast<size_t>(lj.foot)].translation.y() - goal.ball_m.y();
}

double held_feet_settle_m(const std::array<bool, 2>& held, const std::array<double, 2>& error_m) {
  if (held[0] && held[1]) {
    if (error_m[0] * error_m[1] <= 0.0) return 0.0;
    return -(std::abs(error_m[0]) < std::abs(error_m[1]) ? error_m[0] : error_m[1]);
  }
  if (held[0]) return -error_m[0];
  if (held[1]) return -error_m[1];
  return 0.0;
}

bool settle_held_feet(const CorrectorModel& model, const CorrectorState& s, int c, Pose& pose) {
  const std::array<bool, 2> held = {s.foot_holds[static_cast<size_t>(2 * c)].held(),
                                    s.foot_holds[static_cast<size_t>(2 * c + 1)].held()};
  if (!held[0] && !held[1]) return false;
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const BoneTransforms bones = forward_kinematics(shape, pose);
  std::array<double, 2> error{};
  for (int side = 0; side < 2; ++side)
    if (held[static_cast<size_t>(side)])
      error[static_cast<size_t>(side)] = held_height_error_m(model, s, c, side, bones);
  double dy = held_feet_settle_m(held, error);
  const double cap = model.params.foot_pop_budget_m;
  if (cap > 0.0) dy = std::clamp(dy, -cap, cap);
  if (dy < 0.0) {  // lowering: no foot is pushed into the ground (see the header)
    const WorldCapsules capsules = world_capsules(shape, bones);
    for (int side = 0; side < 2; ++side) {
      const double floor_m = held[static_cast<size_t>(side)] ? -model.params.depenetration_tolerance_m : 0.0;
      const double sole = foot_sole_height_m(capsules, leg_joints(kLegSides[side]));
      dy = std::max(dy, std::min(floor_m, sole) - sole);
    }
  }
  if (!(std::abs(dy) > model.params.foot_hold_tolerance_m)) return false;
  pose.root_position_m.y() += dy;
  return true;
}

void stage_settle_feet(const CorrectorModel& model, CorrectorState& s) {
  if (!model.params.held_feet_at_input_height || s.stats.rejected || !s.foot_holds_enabled) return;
  // The characters the depenetration pass posed this step had their held feet's heights among its rows
  // (stage_depenetrate.cpp): settling them here would undo the separations the same rows traded for.
  const std::vector<int>& in_pass = s.depenetration.characters;
  for (int c = 0; c < model.characters(); ++c) {  // serial: one forward kinematics per walking character
    const auto cc = static_cast<size_t>(c);
    if (std::binary_search(in_pass.begin(), in_pass.end(), c)) continue;
    if (!settle_held_feet(model, s, c, s.output[cc])) continue;
    set_bones_from_pose(model, c, s.output[cc], s.com_m, s.rotation);
    for (size_t j = 0; j < kJointCount; ++j)  // the release's rate limit starts from what is output
      s.output_deviation[cc * kJointCount + j] =
          (s.target[cc].local_rotations[j].conjugate() * s.output[cc].local_rotations[j]).normalized();
  }
}

}  // namespace crowdlab
