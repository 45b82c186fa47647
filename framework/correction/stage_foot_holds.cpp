// Foot holds: planted feet stay exactly where they landed (ours; seed 000 §3.3 only says the feet get
// higher gains "to avoid footskate", which bounds but does not remove the slide once neighbours push
// the legs). Two parts, both per character and per foot:
//
//   update_foot_holds (stage_targets)  A joint of the foot (ankle, ball) is PLANTED while its target
//       moves slower than foot_plant_speed_mps and stays below foot_plant_height_m: the input holds it
//       on the ground. When a joint becomes planted its anchor is where the corrected animation has
//       it now (the last output), so a hold never pulls a foot back to the input's spot. While either
//       joint is held, the foot's world rotation is the input's, turned by the offset the output had
//       from the input when the hold began (heel rise and toe roll follow the input); the offset's tilt
//       (its part that is not a turn about the vertical) goes back to 0 at free_joint_return_radps
//       while the hold lasts, so the foot keeps the heading the correction gave it and stands as flat
//       as the input's (return_foot_tilt). Holding the whole offset kept the tilt a contact had given
//       the swinging foot for the whole stance: feet landing 10-20 deg toe-up stood on their heels with
//       the toes 3-6 cm up (issue 27, the corridor's planted-foot float); dropping the tilt at once
//       turned feet by up to 20 deg in one frame (foot pops). With lift_off_knees a foot held at its
//       ball only whose knee's flexion is off the input's by more than kLiftOffKneeTurns rate turns
//       pivots about the ball until the input lifts it (FootHold::pivot_on_ball; issue 27, sessions
//       17-18).
//   hold_feet (stage_integrate)  after the projection to a pose, a held foot more than
//       foot_hold_tolerance_m from its anchor is put back by the least-change two-bone leg IK
//       (core/leg_ik.hpp, reach_ankle: the knee flexes about its own bend axis, about its hinge when
//       the leg is nearly straight, and the leg swings about the hip, so the solved leg's twists stay). The
//       IK moves it horizontally only: the height stays the solve's, whose planted-foot spring pulls it to
//       the input's height (foot_goal), so the ground can still lift a foot. For a rolling foot held at the
//       ball only, the ankle goes where the ball anchor and the foot rotation put it. If the leg cannot
//       reach, the pelvis is lowered first; if it moved, both held feet are re-planted. A foot that pivots
//       on its ball has its ankle goal where the knee's flexion, turned back toward the input's at the
//       rate, reaches from the hip (pivot_about_ball): the heel, not the ball, takes the knee's return.
//       The bones are then
//       rebuilt from that pose, so the next step starts from the held foot.
//   keep_feet_above_ground (end of hold_feet, params.feet_above_input_ground; issue 27, session 17)
//       a foot, held or swinging, whose sole lies more than 5 mm below the input's ground, min(0, the
//       input's sole), is lifted back to 5 mm below it by the same leg IK, its world rotation kept. Traced
//       per stage on the corridor (docs/correction.md, session 17), the correction's feet below the ground
//       are those of bodies standing 7-22 mm lower than the input's: the projection to a pose puts a foot
//       where the lowered leg ends (+3.8 mm per step on swinging feet, against -2.5 mm from the ground
//       springs of the solve), and the depenetration pass and the pelvis drop of hold_feet add 3-5 mm on held
//       feet. Off by default: the lifts flip knees and ankles (the numbers are in corrector_params.hpp).
//
// The same criterion (1 mm per frame at 30 fps, 15 cm) defines "planted" in the quality measure
// (metrics/correction_quality.hpp), the usual foot-contact test on joint speed and height (e.g.
// Ikemoto, Arikan & Forsyth 2006, "Knowing when to put your foot down"). While a foot is held its
// horizontal world spring in the solve pulls it to the anchor; a swinging foot has no world spring
// and gives way to contacts like any other limb. A foot farther sideways than the leg is long goes as
// far as the leg allows and the anchor follows (real skate; not seen on the gomez2024 scenarios).
#include <algorithm>
#include <array>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
namespace {
constexpr bool kKeepSolvedHeight = true;
constexpr double kTiltReturn_radps = 1.0;
/// A foot held at its ball only whose knee deviates from the input's flexion by more than this many turns
/// of free_joint_return_radps x h pivots about its ball (lift_off_knees; issue 27, sessions 17-18). The
/// stance can keep a held leg 15-37 deg straighter than the input's (its pelvis pushed off the planted
/// foot); at the end of the hold the Newton step's pull turned it back within 1-3 frames (a flip), half of
/// the corridor's knee flips at 6.66 /m^2. Session 17 let the ball go (the knee then returned at the rate,
/// limited_now in stage_free_joints.cpp): on the 3 s corridor clip at 6.66 /m^2, 2 turns (13 deg) left 110
/// flips but a stance drift p99 of 19 mm, 3 turns 140-175 flips with 2 foot pops in one of three runs, 4
/// turns 144-188 flips (main 188-218), no pops; but the ball the input still planted slid with the leg (the
/// 2 s walking corridor's foot skate max 2.8 -> 17.2 cm). Pivoting, the ball stays held: 144-195 flips,
/// skate as without the option (docs/correction.md, session 18).
constexpr double kLiftOffKneeTurns = 4.0;
/// How deep below the input's ground keep_feet_above_ground leaves a foot (m): lifting every foot back
/// to within foot_hold_tolerance_m flipped knees and ankles at 4.44 /m^2 (11-15 -> 24-37 over three runs,
/// docs/correction.md, session 17); lifting only what lies deeper than 5 mm (half the 10 mm
/// target, the depenetration pass's own tolerance) flips 9-22 there.
constexpr double kBelowGroundAllowed_m = 0.005;

bool planted(const CorrectorParams& p, double h, const Vec3& before, const Vec3& now) {
  return (now - before).norm() < p.foot_plant_speed_mps * h && now.y() < p.foot_plant_height_m;
}

/// A held foot out of the leg's reach (the solve pushed the pelvis away from it) would be dragged
/// along. Instead the pelvis is lowered until every held ankle is within the leg's length, the usual pelvis
/// adjustment of foot-locking IK (e.g. Unity's / Unreal's "pelvis offset"): a drop of a few millimetres is
/// invisible where a sliding foot is not. When even a lower pelvis cannot reach (the foot is farther sideways
/// than the leg is long), the hip is pulled toward it.
bool lower_pelvis_to_reach(const BodyShape& shape, const std::array<FootGoal, 2>& goals,
                           const std::array<bool, 2>& held, Pose& pose) {
  constexpr double kReachMargin_m = 1e-7;  // reach_ankle's clamp would otherwise bite
  const Vec3 root_before = pose.root_position_m;
  for (int round = 0; round < 2; ++round) {  // a second round when the other leg's fix moved the hip
    for (int side = 0; side < 2; ++side) {
      if (!held[static_cast<size_t>(side)]) continue;
      const Vec3 to_hip =
          hip_position(shape, pose, kLegSides[side]) - goals[static_cast<size_t>(side)].ankle_m;
      const double reach = leg_length(shape, kLegSides[side]) - kReachMargin_m;
      if (to_hip.norm() <= reach) continue;
      const double horizontal2 = to_hip.x() * to_hip.x() + to_hip.z() * to_hip.z();
      if (horizontal2 < reach * reach) {
        pose.root_position_m.y() -= to_hip.y() - std::sqrt(reach * reach - horizontal2);
      } else {
        pose.root_position_m -= to_hip * (1.0 - reach / to_hip.norm());
      }
    }
  }
  return pose.root_position_m != root_before;
}

/// Whether character c's knee deviates from the input's flexion (its last output's turn about the hinge)
/// by more than kLiftOffKneeTurns rate turns (params.lift_off_knees, issue 27, session 17).
bool knee_bent_off_input(const CorrectorModel& model, const CorrectorState& s, int c, int knee) {
  return knee_flexion_off_input_rad(s, c, knee) >
         kLiftOffKneeTurns * model.params.free_joint_return_radps * model.h;
}
}  // namespace

Quat return_foot_tilt(const Quat& offset, double max_turn_rad) {
  // Swing-twist decomposition about the world vertical: the twist keeps w and the y component.
  const double norm = std::hypot(offset.w(), offset.y());
  const Quat twist = norm < 1e-9 ? Quat::Identity() : Quat(offset.w() / norm, 0.0, offset.y() / norm, 0.0);
  const Quat swing = (offset * twist.conjugate()).normalized();
  const double angle = swing.angularDistance(Quat::Identity());
  if (!(angle > max_turn_rad)) return twist;
  return (Quat::Identity().slerp(1.0 - max_turn_rad / angle, swing) * twist).normalized();
}

void update_foot_holds(const CorrectorModel& model, CorrectorState& s, int c,
                       const std::array<Quat, 2>& old_target_foot_rotation) {
  const CorrectorParams& p = model.params;
  const size_t base = static_cast<size_t>(c) * kJointCount;
  for (int side = 0; side < 2; ++side) {
    FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
    if (!s.foot_holds_enabled) {
      hold = FootHold{};
      continue;
    }
    const LegJoints lj = leg_joints(kLegSides[side]);
    const size_t ankle = base + static_cast<size_t>(lj.ankle), ball = base + static_cast<size_t>(lj.foot);
    const bool ankle_planted = planted(p, model.h, s.target_origin_old_m[ankle], s.target_origin_m[ankle]);
    const bool ball_planted = planted(p, model.h, s.target_origin_old_m[ball], s.target_origin_m[ball]);
    // lift_off_knees: a rolling foot whose knee is far off the input's flexion pivots about its ball until
    // the input lifts the ball or sets its heel down (pivot_about_ball). Let go instead (session 17), the
    // ball slid with the leg while its knee returned.
    hold.pivot_on_ball = p.lift_off_knees && !ankle_planted && ball_planted &&
                         (hold.pivot_on_ball || knee_bent_off_input(model, s, c, lj.knee));
    if ((ankle_planted || ball_planted) && !hold.held())
      hold.rotation_offset =
          (s.rotation[ankle] * old_target_foot_rotation[static_cast<size_t>(side)].conjugate()).normalized();
    if (ankle_planted || ball_planted)
      hold.rotation_offset = return_foot_tilt(hold.rotation_offset, kTiltReturn_radps * model.h);
    if (ankle_planted && !hold.ankle) hold.ankle_anchor_m = bone_origin(model, s, static_cast<int>(ankle));
    if (ball_planted && !hold.ball) hold.ball_anchor_m = bone_origin(model, s, static_cast<int>(ball));
    hold.ankle = ankle_planted;
    hold.ball = ball_planted;
    hold.given_way_m = 0.0;
  }
}

namespace {
/// The input's height of character c's ankle (or ball) of `side` now, reached from where the last output
/// had it at most at the foot motion budget: per step, the input's vertical motion plus foot_pop_budget_m
/// (an unlimited pull threw feet: docs/correction.md).
double input_height_within_budget(const CorrectorModel& model, const CorrectorState& s, int c, int side,
                                  bool ball) {
  const LegJoints lj = leg_joints(kLegSides[side]);
  const size_t joint = static_cast<size_t>(c) * kJointCount + static_cast<size_t>(ball ? lj.foot : lj.ankle);
  const double y = s.target_origin_m[joint].y();
  if (!(model.params.foot_pop_budget_m > 0.0)) return y;
  const double start_y = s.foot_start_m[static_cast<size_t>(4 * c + side + (ball ? 2 : 0))].y();
  const double step = std::abs(y - s.target_origin_old_m[joint].y()) + model.params.foot_pop_budget_m;
  return std::clamp(y, start_y - step, start_y + step);
}
}  // namespace

FootGoal foot_goal(const CorrectorModel& model, const CorrectorState& s, int c, int side) {
  const FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const LegJoints lj = leg_joints(kLegSides[side]);
  const size_t ankle = static_cast<size_t>(c) * kJointCount + static_cast<size_t>(lj.ankle);
  FootGoal g;
  g.rotation = (hold.rotation_offset * s.target_rotation[ankle]).normalized();
  const Vec3 ball_offset = g.rotation * shape.joint_offsets_m[static_cast<size_t>(lj.foot)];
  g.ankle_m = hold.ankle ? hold.ankle_anchor_m : Vec3(hold.ball_anchor_m - ball_offset);
  g.ball_m = hold.ball ? hold.ball_anchor_m : Vec3(g.ankle_m + ball_offset);
  // Height: the input's, the foot's ground contact as the input plants it (the correction moves bodies
  // sideways, not up; held horizontally only, whole bodies floated on their planted feet). A foot that
  // is off that height goes back at most at the foot motion budget: per step, its input's vertical
  // motion plus foot_pop_budget_m, from where the last output had it (an unlimited pull threw feet:
  // docs/correction.md). The solve's planted-foot spring pulls to it (stage_assemble.cpp); the IK in
  // hold_feet keeps the solve's height.
  const double shift = input_height_within_budget(model, s, c, side, false) - g.ankle_m.y();
  g.ankle_m.y() += shift;
  g.ball_m.y() += shift;
  if (hold.ball && model.params.held_feet_at_input_height) {
    // The ball's own height is the input's too (issue 27, session 12). Shifted with the ankle only, a
    // ball anchor kept the height it landed at above the ankle: a foot that landed toes-up stood toes-up
    // for the whole stance (ball 8-13 cm above the input's, ankle at its height), whatever its rotation
    // goal said. A rolling foot held at the ball only hangs its ankle from the ball.
    g.ball_m.y() = input_height_within_budget(model, s, c, side, true);
    if (!hold.ankle) g.ankle_m = g.ball_m - ball_offset;
  }
  return g;
}

namespace {
/// The distance (m) from the hip to the ankle of character c's leg `side` with its knee's flexion off the
/// input's turned back toward none by at most free_joint_return_radps x h from the last output's.
double rate_limited_leg_reach_m(const CorrectorModel& model, const CorrectorState& s, int c, int side) {
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const LegJoints lj = leg_joints(kLegSides[side]);
  const double twist_rad = knee_flexion_twist_off_input_rad(s, c, lj.knee);
  const double sign = twist_rad < 0.0 ? -1.0 : 1.0;
  const double left_rad = std::max(0.0, std::abs(twist_rad) - model.params.free_joint_return_radps * model.h);
  const Quat knee = (s.target[static_cast<size_t>(c)].local_rotations[static_cast<size_t>(lj.knee)] *
                     Quat(Eigen::AngleAxisd(sign * left_rad, Vec3::UnitX())))
                        .normalized();
  return (shape.joint_offsets_m[static_cast<size_t>(lj.knee)] +
          knee * shape.joint_offsets_m[static_cast<size_t>(lj.ankle)])
      .norm();
}

/// A foot held at its ball whose knee is far off the input's flexion (FootHold::pivot_on_ball) pivots about
/// the ball: its ankle goal is the point nearest the held foot's at the rate-limited knee's reach from the
/// hip and the foot's length from the ball, and the foot turns to point from it to the ball.
void pivot_about_ball(const CorrectorModel& model, const CorrectorState& s, int c, int side, const Pose& pose,
                      FootGoal& g) {
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const LegJoints lj = leg_joints(kLegSides[side]);
  const Vec3 hip = hip_position(shape, pose, kLegSides[side]);
  const Vec3 foot = g.rotation * shape.joint_offsets_m[static_cast<size_t>(lj.foot)];
  const double length = foot.norm(), apart = (g.ball_m - hip).norm();
  if (!(apart > length) || !(length > 0.0)) return;
  const double reach =
      std::clamp(rate_limited_leg_reach_m(model, s, c, side), apart - length, apart + length);
  const Vec3 along = (g.ball_m - hip) / apart;
  const double x = (apart * apart + reach * reach - length * length) / (2.0 * apart);
  const double radius = std::sqrt(std::max(0.0, reach * reach - x * x));
  Vec3 across = (g.ankle_m - hip) - along * along.dot(g.ankle_m - hip);
  if (across.norm() < 1e-9) return;
  across.normalize();
  const Vec3 ankle = hip + along * x + across * radius;
  g.rotation = (Quat::FromTwoVectors(foot, g.ball_m - ankle) * g.rotation).normalized();
  g.ankle_m = ankle;
}

/// The held feet re-planted (the header's hold_feet).
void hold_held_feet(const CorrectorModel& model, CorrectorState& s, int c, Pose& pose) {
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const std::array<bool, 2> held = {s.foot_holds[static_cast<size_t>(2 * c)].held(),
                                    s.foot_holds[static_cast<size_t>(2 * c + 1)].held()};
  if (!held[0] && !held[1]) return;
  const BoneTransforms solved = forward_kinematics(shape, pose);
  std::array<FootGoal, 2> goals;
  std::array<bool, 2> fix = {false, false};
  for (int side = 0; side < 2; ++side) {
    if (!held[static_cast<size_t>(side)]) continue;
    FootGoal& g = goals[static_cast<size_t>(side)];
    g = foot_goal(model, s, c, side);
    const LegJoints lj = leg_joints(kLegSides[side]);
    const Vec3& ankle = solved[static_cast<size_t>(lj.ankle)].translation;
    const Vec3& ball = solved[static_cast<size_t>(lj.foot)].translation;
    // Height: the solve's. Its planted-foot spring pulls the foot to the input's height, and the ground
    // can still lift a foot; re-planting it here too held the legs so hard that neighbours' legs stayed
    // inside each other (docs/correction.md).
    const double lift = kKeepSolvedHeight ? ankle.y() - g.ankle_m.y() : 0.0;
    g.ankle_m.y() += lift;
    g.ball_m.y() += lift;
    if (s.foot_holds[static_cast<size_t>(2 * c + side)].pivot_on_ball)
      pivot_about_ball(model, s, c, side, pose, g);
    // Within tolerance the solve's leg is kept as it is: a near-straight leg turns a sub-millimetre
    // ankle correction into degrees of knee rotation, which would show as deviation, not as motion.
    const double tol = model.params.foot_hold_tolerance_m;
    fix[static_cast<size_t>(side)] = (ankle - g.ankle_m).norm() >= tol || (ball - g.ball_m).norm() >= tol;
  }
  if (!fix[0] && !fix[1]) return;
  // Moving the pelvis for one leg moves the other leg's foot too: every held foot is then re-planted.
  if (lower_pelvis_to_reach(shape, goals, held, pose)) fix = held;
  for (int side = 0; side < 2; ++side) {
    if (!fix[static_cast<size_t>(side)]) continue;
    FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
    const LegJoints lj = leg_joints(kLegSides[side]);
    const FootGoal& goal = goals[static_cast<size_t>(side)];
    if (reach_ankle(shape, pose, kLegSides[side], goal.ankle_m, goal.rotation) > 0.0) {
      // Out of reach even so: the foot lands as near as the leg allows, and the anchors move there.
      const BoneTransforms reached = forward_kinematics(shape, pose);
      hold.ankle_anchor_m = reached[static_cast<size_t>(lj.ankle)].translation;
      hold.ball_anchor_m = reached[static_cast<size_t>(lj.foot)].translation;
    }
  }
}
}  // namespace

double foot_sole_height_m(const WorldCapsules& capsules, const LegJoints& leg) {
  double y = 1e9;
  for (int b : {leg.ankle, leg.foot}) {
    const Capsule& cap = capsules[static_cast<size_t>(b)];
    y = std::min(y, std::min(cap.a.y(), cap.b.y()) - cap.radius_m);
  }
  return y;
}

int keep_feet_above_ground(const CorrectorModel& model, const CorrectorState& s, int c, Pose& pose) {
  if (!model.params.feet_above_input_ground) return 0;
  const BodyShape& shape = model.bodies[static_cast<size_t>(c)].shape;
  const BoneTransforms bones = forward_kinematics(shape, pose);
  const WorldCapsules capsules = world_capsules(shape, bones);
  const double tol = model.params.foot_hold_tolerance_m;
  WorldCapsules input{};
  bool have_input = false;  // the input's capsules only for a foot below y = 0 (most steps have none)
  int lifted = 0;
  for (int side = 0; side < 2; ++side) {
    const LegJoints lj = leg_joints(kLegSides[side]);
    const double sole_m = foot_sole_height_m(capsules, lj);
    if (sole_m >= -kBelowGroundAllowed_m - tol) continue;  // the input's ground is at most y = 0
    if (!have_input) {
      input = world_capsules(shape, s.target[static_cast<size_t>(c)]);
      have_input = true;
    }
    const double depth_m = std::min(0.0, foot_sole_height_m(input, lj)) - kBelowGroundAllowed_m - sole_m;
    if (!(depth_m > tol)) continue;
    // The other leg's bones do not move: the IK edits only this leg's hip, knee and ankle rotations.
    const RigidTransform& ankle = bones[static_cast<size_t>(lj.ankle)];
    reach_ankle(shape, pose, kLegSides[side], ankle.translation + Vec3(0.0, depth_m, 0.0), ankle.rotation);
    ++lifted;
  }
  return lifted;
}

void hold_feet(const CorrectorModel& model, CorrectorState& s, int c, Pose& pose) {
  hold_held_feet(model, s, c, pose);
  keep_feet_above_ground(model, s, c, pose);
}

}  // namespace crowdlab
