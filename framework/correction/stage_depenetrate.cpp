// Position-level depenetration of the projected poses (ours; seed 000 takes one Newton step and keeps
// what it leaves). After stage_integrate has projected every character to a pose and re-planted its
// held feet, inter-body capsule pairs still deeper than depenetration_tolerance_m are pushed apart by
// moving the poses directly: a post-stabilisation pass in the sense of Cline & Pai 2003
// ("Post-stabilization for rigid body simulation with contact and constraints") and of position-based
// dynamics' contact projection (Mueller et al. 2007, "Position based dynamics").
//
// Why a separate pass: the one Newton step leaves deep residuals where it cannot move a limb far
// enough in one frame. Measured on gomez2024's corridor at 3.33 /m^2 (docs/correction.md): of the
// contacts ending > 1 cm deep, 58 % were left > 1 cm deep by the linear solve itself (the limb's
// inertia and the control's damper resist a 5 cm move within 1/30 s, whatever the contact stiffness),
// 39 % were separated by the solve but pushed back by the projection and the foot holds, and 3 % by the
// linearisation. The p99 inter-body depth was 13-59 mm; with the pass it is 0.1-8.6 mm.
//
// The pass, repeated up to depenetration_passes times (it stops when nothing is deeper):
//   1. contacts   the capsule pairs the narrow phase listed as near (bounding spheres within
//                 kNearMargin_m at the predicted state, corrector_state.hpp) that the current poses
//                 put deeper than the tolerance: depth delta, normal n (b -> a), axis points p_a, p_b.
//                 The first pass tests every listed pair, later ones the pairs of the characters the
//                 last pass moved;
//   2. split      each contact's separation delta is shared between its two characters in proportion
//                 to their compliance along n (below), so a body whose feet are held yields less;
//   3. solve      per character, the pose change of least control-spring energy
//                     min 1/2 sum_j k_j |w_j|^2 + 1/2 k_root |dr|^2
//                     s.t. n . J_p [dr; w] = share * delta   for each of its contacts,
//                          e . J_q [dr; w] = 0               for the x, y and z of each held foot joint
//                                                            (y: w_h (y*_q - y_q) with
//                                                            held_feet_at_input_height, y* its goal
//                                                            height, weighted kHeldHeightRowWeight: the
//                                                            contacts win; issue 27, session 13),
//                          u . J_f [dr; w] = allowed - moved for each foot joint f over its budget
//                                                            (weighted kFootBudgetRowWeight: it wins),
//                 the foot motion budget (foot_pop_budget_m, issue 18): a foot joint that moved since
//                 the last output farther than its input moved plus the budget is pulled back along its
//                 direction of motion u, so legs pressed together are separated by the rest of the
//                 bodies and no foot jumps (without it, 69 foot joints of the corridor at 6.66 /m^2
//                 jumped 5-20 cm more than their input in one frame over 4 s). A character with no deep
//                 contact but a foot over budget (or a held foot off its goal height) is solved too;
//                 where w_j is a world-frame rotation about joint j, dr the root translation, k_j the
//                 joint's control spring (CorrectorBody::rot_stiffness, the per-inertia gains of Eq. 4,
//                 pelvis and feet stiffer; floored at k_root kMinLever_m^2) and k_root the root's
//                 translation spring. The point Jacobian of p on bone b is I for dr and (p - o_j) x n
//                 for every joint j from b up to the root (o_j: joint j's world position). The weighted
//                 least-norm solution is dq = K^-1 J^T (J K^-1 J^T + eps)^-1 r, a dense solve of one
//                 row per constraint (a handful; depenetration_solve.hpp);
//   4. apply      root += dr (at most the deepest separation asked for); local_j <- R_parent^T
//                 exp(w_j) R_parent local_j (R_parent: the parent's world rotation before the pass),
//                 each w_j limited to kMaxRotation_rad; held feet are then re-planted exactly by
//                 hold_feet.
//   guards        (issue 27, session 15) before applying: where the change would take a capsule deeper
//                 behind an environment box face than it is (or than the face, when outside), or a capsule
//                 below the ground deeper than it is or than the tolerance, its row n . J_p dq = what it may
//                 still move in is added (weighted kGuardRowWeight) and the character solved again (an
//                 active set, kGuardRounds rounds); and a held foot whose shank or foot is deep in a box
//                 gives way horizontally with that contact (its x and z rows ask for the push, its anchors
//                 move with it), at most kHeldFootGiveWay_m per step.
// Compliance of character c along n at p: sum over the chain of |(p - o_j) x n|^2 / k_j + 1 / k_root,
// the displacement per unit force of the same energy (ignoring the held-foot rows).
//
// Velocities are left as the step computed them: the pass moves positions only (post-stabilisation
// without velocity change), so it removes penetration without adding the energy of the push.
// Work is split over body pairs and characters (TBB) with per-index outputs and fixed-order gathers:
// the result does not depend on the number of threads.
#include <algorithm>
#include <array>
#include <cmath>
#include <tuple>

#include <tbb/parallel_for.h>
#include <Eigen/Cholesky>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/corrector_step.hpp"
#include "framework/correction/depenetration_solve.hpp"
#include "framework/correction/environment_box_contact.hpp"

namespace crowdlab {
namespace {

using namespace depenetration;

/// Floor on each joint's rotation weight: k_j >= k_root (kMinLever_m)^2, so a rotation never moves a
/// point more cheaply than translating the root would at 20 cm from the joint. Without it the least-
/// energy change turned light leaves (toes, hands: tiny effective inertia) by 1-2 rad to move a contact
/// point a few centimetres, which the trust region then cut back: measured on the corridor at 6.66 /m^2,
/// 18 % of the per-character solves were throttled and deep contacts took more passes to clear.
constexpr double kMinLever_m = 0.2;
/// Weight of the foot-budget rows in the regularised solve (rows and right-hand sides scaled by it).
/// Scaling a row leaves the exact solution alone but, where rows conflict and the regularisation
/// compromises, makes its residual cost w^2 times more: the budget is kept and the contact is
/// separated by the rest of the two bodies, a prioritised solve (e.g. Siciliano & Slotine 1991, "A
/// general framework for managing multiple tasks in highly redundant robotic systems") in its
/// weighted-least-squares form. Measured on gomez2024's corridor at 6.66 /m^2 over the paper's 20 s: 1
/// -> 2 foot pops (worst excess 9.3 cm), p99 depth 8.2 mm; 10 -> 0 pops (worst 4.4 cm), 7.6 mm. The
/// remaining pops had been legs pressed between two neighbours, where the contact rows and the budget
/// row of the same foot conflict (docs/correction.md).
constexpr double kFootBudgetRowWeight = 10.0;
/// Weight of the guard rows (as kFootBudgetRowWeight): where they conflict with contacts, they win.
constexpr double kGuardRowWeight = 10.0;
/// Re-solves per character and pass with the guards found so far.
constexpr int kGuardRounds = 2;
/// Capsules within this of a surface (m) are checked: one pass moves a point by a few centimetres.
constexpr double kGuardMargin_m = 0.08;
/// A guard is added when the change would take a capsule more than this (m) past what it may reach.
constexpr double kGuardSlack_m = 0.001;
/// The directions in which a held foot joint may not move in the pass: x, z and (issue 27) y. With x
/// and z only, a contact on the leg that the held foot's rows kept from moving it sideways was met by
/// turning the leg about the hip, which lifts the foot; hold_feet then put it back horizontally at the
/// lifted height, pass after pass: planted feet rose up to 2 cm per step (the foot motion budget) to
/// 5-17 cm (the corridor's planted-foot float, p99 47 mm at 6.66 /m^2, docs/correction.md).
constexpr int kHeldFootRows = 3;
constexpr std::array<int, 3> kHeldFootAxes = {0, 2, 1};
/// Weight of the held feet's height rows (issue 27, session 13; rows and right-hand sides scaled by it,
/// as kFootBudgetRowWeight but below 1): where a contact and a foot's height conflict (a body pressed
/// between neighbours is lifted by their contacts' vertical parts), the regularised solve keeps the
/// contact and leaves the height to later passes and steps, a prioritised solve with the feet second.
/// Measured on 3 s corridor clips at 6.66 /m^2 (docs/correction.md, session 13): weight 1 brought the
/// planted-foot float p99 30.8 -> 16.2 mm but the p99 inter-body depth 9.6 -> 14.4 mm (the feet's rows
/// undid separations pass after pass, as session 12's settle after the pass did); 0.1 kept the depth
/// (9.4 mm) with the same float, but not on the standing crowd at 6.66 /m^2 (9.4 -> 14.0 mm): one reason
/// held_feet_at_input_height stays off.
constexpr double kHeldHeightRowWeight = 0.1;
/// How far (m) a held foot may give way per step when the lower leg above it is deep in an environment
/// box (issue 27, session 15). The held foot's x, y and z rows pin the bottom of the shank and the foot
/// capsules: a foot that landed a few centimetres nearer a barrier than the input's (its swing pushed by
/// neighbours) left the shank 11-14 mm inside it for the whole stance (corridor 6.66 /m^2, 3 s: every
/// capsule-frame deeper than 5 mm after the surface guards was a thigh or shank of a leg whose foot was
/// held). The foot's x and z rows then ask for the contact's horizontal push and its anchors move with
/// it, at most this far per step: a slide the stance drift measure sees (docs/correction.md).
constexpr double kHeldFootGiveWay_m = 0.01;
/// Characters whose body box at the predicted state comes within this of an environment box are tested
/// against the boxes (m): the pass moves a body by at most a few centimetres per pass.
constexpr double kEnvironmentMargin_m = 0.1;
/// Largest separation (m) one pass asks of a box contact: a leg 5-9 cm deep in a barrier pushed out
/// in one pass took its foot along past the foot motion budget (foot pops; docs/correction.md). The
/// rest is left to the next passes and steps.
constexpr double kMaxEnvironmentPush_m = 0.02;

/// The row n . J_p of a point p (world) moving with bone `bone` (local index), for a unit direction n.
Row point_row(const BoneTransforms& bones, int bone, const Vec3& p, const Vec3& n) {
  Row row = Row::Zero();
  row.head<3>() = n.transpose();
  for (int j = bone; j >= 0; j = kJointParent[static_cast<size_t>(j)]) {
    row.segment<3>(3 + 3 * j) = (p - bones[static_cast<size_t>(j)].translation).cross(n).transpose();
    if (j == 0) break;
  }
  return row;
}

/// K^-1: the inverse control springs of the root translation and of every joint.
Weights inverse_weights(const CorrectorBody& body) {
  Weights w;
  w.head<3>().setConstant(1.0 / body.root_translation_stiffness);
  const double floor = body.root_translation_stiffness * kMinLever_m * kMinLever_m;
  for (int j = 0; j < kJointCount; ++j)
    w.segment<3>(3 + 3 * j).setConstant(1.0 / std::max(floor, body.rot_stiffness[static_cast<size_t>(j)]));
  return w;
}

/// Displacement per unit force (m/N) of the point of `row` along its direction, J K^-1 J^T.
double compliance(const Row& row, const Weights& inv_w) {
  return row.cwiseAbs2().dot(inv_w.transpose());
}

/// The capsule pairs among `candidates` deeper than `tolerance`, with the compliance split.
void find_deep_contacts(const DepenetrationScratch& w, int ci, int cj, const NearCapsulePairs& candidates,
                        double tolerance, std::vector<DeepContact>& out) {
  out.clear();
  const auto ii = static_cast<size_t>(ci), jj = static_cast<size_t>(cj);
  for (const auto& [a, b] : candidates) {
    // Boxes first: most listed pairs are a few centimetres apart, and overlapping capsules overlap
    // in every axis.
    if (!w.boxes[ii][a].overlaps(w.boxes[jj][b])) continue;
    const CapsuleContact cc = capsule_contact(w.capsules[ii][a], w.capsules[jj][b]);
    if (!(cc.depth_m > tolerance)) continue;
    DeepContact d;
    d.bone_a = ci * kJointCount + a;
    d.bone_b = cj * kJointCount + b;
    d.depth_m = cc.depth_m;
    d.normal = cc.normal;
    d.point_a = cc.point_a;
    d.point_b = cc.point_b;
    const double comp_a = compliance(point_row(w.bones[ii], a, cc.point_a, cc.normal), w.inverse_weights[ii]);
    const double comp_b = compliance(point_row(w.bones[jj], b, cc.point_b, cc.normal), w.inverse_weights[jj]);
    d.share_a = comp_a / (comp_a + comp_b);
    out.push_back(d);
  }
}

/// Character c's capsules deeper than `tolerance` in an environment box (environment_box_contact.hpp):
/// the box does not move, so c takes the whole separation (share 1; bone_b = -1).
void find_environment_contacts(const CorrectorModel& model, const DepenetrationScratch& w, int c,
                               double tolerance, std::vector<DeepContact>& out) {
  out.clear();
  const auto cc = static_cast<size_t>(c);
  const Vec3& root = w.capsules[cc][0].a;
  EnvironmentBoxContact e;
  for (size_t k = 0; k < model.environment_boxes.size(); ++k)
    for (int b = 0; b < kJointCount; ++b) {
      if (!w.boxes[cc][static_cast<size_t>(b)].overlaps(model.environment_box_bounds[k])) continue;
      if (!environment_box_contact(w.capsules[cc][static_cast<size_t>(b)], model.environment_boxes[k], root,
                                   tolerance, e))
        continue;
      DeepContact d;
      d.bone_a = c * kJointCount + b;
      d.depth_m = e.penetration_m;
      d.normal = e.normal;
      d.point_a = e.axis_point;
      d.share_a = 1.0;
      out.push_back(d);
    }
}

/// Whether character c's body (its box at the predicted state, grown by `margin`) reaches an
/// environment box: such characters are tested against the boxes by the pass.
bool near_environment(const CorrectorModel& model, const CorrectorState& s, int c, double margin) {
  Aabb body = s.body_box[static_cast<size_t>(c)];
  body.lo -= Vec3::Constant(margin);
  body.hi += Vec3::Constant(margin);
  for (const Aabb& bounds : model.environment_box_bounds)
    if (body.overlaps(bounds)) return true;
  return false;
}

/// Rows pulling character c's foot joints back onto their motion budget: a joint that moved
/// farther since the last output (foot_start_m) than its input did plus `budget` gets the row
/// u . J_x dq = allowed - moved along its direction of motion u (see foot_pop_budget_m).
struct FootRows {
  std::array<Row, 4> row;
  std::array<double, 4> r{};
  int count = 0;
};
FootRows foot_budget_rows(const CorrectorState& s, int c, double budget, const BoneTransforms& bones) {
  FootRows out;
  if (!(budget > 0.0)) return out;
  const auto cc = static_cast<size_t>(c);
  for (size_t k = 0; k < kFootJointOrder.size(); ++k) {
    const int joint = kFootJointOrder[k];
    const size_t g = cc * kJointCount + static_cast<size_t>(joint);
    const double allowed = (s.target_origin_m[g] - s.target_origin_old_m[g]).norm() + budget;
    const Vec3& x = bones[static_cast<size_t>(joint)].translation;
    const Vec3 d = x - s.foot_start_m[4 * cc + k];
    const double moved = d.norm();
    if (!(moved > allowed)) continue;
    const auto i = static_cast<size_t>(out.count++);
    out.row[i] = point_row(bones, kJointParent[static_cast<size_t>(joint)], x, d / moved);
    out.r[i] = allowed - moved;
  }
  return out;
}

/// The height (m) the pass asks of each held foot joint of character c (side, then ankle 0 / ball 1):
/// with held_feet_at_input_height its goal's (foot_goal: the input's, approached at most at the foot
/// motion budget), else where it is (the session-11 rows: a held foot does not move in the pass).
using HeldHeights = std::array<std::array<double, 2>, 2>;
HeldHeights held_heights(const CorrectorModel& model, const CorrectorState& s, int c,
                         const BoneTransforms& bones) {
  HeldHeights y{};
  for (int side = 0; side < 2; ++side) {
    const LegJoints lj = leg_joints(kLegSides[side]);
    auto& out = y[static_cast<size_t>(side)];
    out = {bones[static_cast<size_t>(lj.ankle)].translation.y(),
           bones[static_cast<size_t>(lj.foot)].translation.y()};
    if (!model.params.held_feet_at_input_height || !s.foot_holds[static_cast<size_t>(2 * c + side)].held())
      continue;
    const FootGoal goal = foot_goal(model, s, c, side);
    out = {goal.ankle_m.y(), goal.ball_m.y()};
  }
  return y;
}

/// Whether a held foot of character c stands off its goal height by more than the hold tolerance, so
/// that c is solved even without a deep contact (only with held_feet_at_input_height).
bool held_feet_off_height(const CorrectorModel& model, const CorrectorState& s, int c,
                          const BoneTransforms& bones) {
  if (!model.params.held_feet_at_input_height) return false;
  for (int side = 0; side < 2; ++side)
    if (s.foot_holds[static_cast<size_t>(2 * c + side)].held() &&
        std::abs(held_height_error_m(model, s, c, side, bones)) > model.params.foot_hold_tolerance_m)
      return true;
  return false;
}

/// Bones whose environment contacts let the held foot of their leg give way (kHeldFootGiveWay_m): the
/// shank and the foot, whose capsules end at the held joints, so that no pose change with the foot held
/// takes them out of a box.
bool lower_leg_bone(int bone, const LegJoints& lj) {
  return bone == lj.knee || bone == lj.ankle || bone == lj.foot;
}

/// The horizontal move (m, world) each held foot of character c makes in this pass: along the horizontal
/// part of the normal of the deepest box contact on its lower leg, as deep as that contact (at most
/// kMaxEnvironmentPush_m per pass), within what is left of kHeldFootGiveWay_m this step; 0 without one.
std::array<Vec3, 2> held_feet_give_way(const CorrectorState& s, int c,
                                       const std::vector<const DeepContact*>& contacts) {
  std::array<Vec3, 2> move = {Vec3::Zero(), Vec3::Zero()};
  for (int side = 0; side < 2; ++side) {
    const FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
    if (!hold.held()) continue;
    const LegJoints lj = leg_joints(kLegSides[side]);
    const DeepContact* deepest = nullptr;
    for (const DeepContact* d : contacts)
      if (d->bone_b < 0 && lower_leg_bone(d->bone_a % kJointCount, lj) &&
          (deepest == nullptr || d->depth_m > deepest->depth_m))
        deepest = d;
    if (deepest == nullptr) continue;
    const Vec3 horizontal(deepest->normal.x(), 0.0, deepest->normal.z());
    const double length = horizontal.norm(), left = kHeldFootGiveWay_m - hold.given_way_m;
    if (!(length > 1e-6) || !(left > 0.0)) continue;
    move[static_cast<size_t>(side)] =
        horizontal / length * std::min({deepest->depth_m, kMaxEnvironmentPush_m, left});
  }
  return move;
}

/// Rows of the constraint system of character c: its contacts (the deepest, if more than fit), then
/// the x, y and z of its held foot joints (x and z stay, y goes to held_heights: the feet's height is
/// traded against the contacts in the same solve, issue 27), then its foot joints over budget.
void constraint_rows(const CorrectorModel& model, const CorrectorState& s, int c, const BoneTransforms& bones,
                     std::vector<const DeepContact*>& contacts, const FootRows& feet,
                     const std::array<Vec3, 2>& give_way, RowBlock& J, SmallVector& r) {
  int held_rows = 0;
  for (int f = 2 * c; f < 2 * c + 2; ++f)
    held_rows += kHeldFootRows * (int{s.foot_holds[static_cast<size_t>(f)].ankle} +
                                  int{s.foot_holds[static_cast<size_t>(f)].ball});
  const int room = kMaxRows - held_rows - feet.count;
  if (static_cast<int>(contacts.size()) > room) {
    std::stable_sort(contacts.begin(), contacts.end(),
                     [](const DeepContact* x, const DeepContact* y) { return x->depth_m > y->depth_m; });
    contacts.resize(static_cast<size_t>(room));
  }
  const int m = static_cast<int>(contacts.size()) + held_rows + feet.count;
  J.resize(m, kVariables);
  r.resize(m);
  int i = 0;
  for (const DeepContact* d : contacts) {
    const bool side_a = d->bone_a / kJointCount == c;
    const int bone = (side_a ? d->bone_a : d->bone_b) % kJointCount;
    J.row(i) =
        point_row(bones, bone, side_a ? d->point_a : d->point_b, side_a ? d->normal : Vec3(-d->normal));
    // A box contact asks for at most kMaxEnvironmentPush_m per pass (see there).
    r(i++) = d->bone_b < 0 ? std::min(d->depth_m, kMaxEnvironmentPush_m)
                           : d->depth_m * (side_a ? d->share_a : 1.0 - d->share_a);
  }
  const HeldHeights heights = held_heights(model, s, c, bones);
  for (int side = 0; side < 2; ++side) {
    const FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
    const LegJoints lj = leg_joints(kLegSides[side]);
    const auto& height = heights[static_cast<size_t>(side)];
    for (const auto& [held, joint, y] :
         {std::tuple{hold.ankle, lj.ankle, height[0]}, std::tuple{hold.ball, lj.foot, height[1]}}) {
      if (!held) continue;
      // A joint's position moves with its parent's chain, not with its own rotation.
      const Vec3& q = bones[static_cast<size_t>(joint)].translation;
      for (int k = 0; k < kHeldFootRows; ++k) {
        const int axis = kHeldFootAxes[static_cast<size_t>(k)];
        J.row(i) = point_row(bones, kJointParent[static_cast<size_t>(joint)], q, Vec3::Unit(axis));
        if (axis == 1 && model.params.held_feet_at_input_height) {
          J.row(i) *= kHeldHeightRowWeight;
          r(i++) = kHeldHeightRowWeight * (y - q.y());
        } else {  // x and z (and y without held_feet_at_input_height) stay, or give way (x, z)
          r(i++) = give_way[static_cast<size_t>(side)][axis];
        }
      }
    }
  }
  for (int k = 0; k < feet.count; ++k) {
    J.row(i) = kFootBudgetRowWeight * feet.row[static_cast<size_t>(k)];
    r(i++) = kFootBudgetRowWeight * feet.r[static_cast<size_t>(k)];
  }
}

/// Character c's capsules within kGuardMargin_m of an environment box (not deeper than `tolerance`:
/// those have contact rows) or of the ground plane, in the pose of the pass (w.bones, w.capsules).
void surface_gaps(const CorrectorModel& model, const DepenetrationScratch& w, int c, double tolerance,
                  std::vector<SurfaceGap>& out) {
  out.clear();
  const auto cc = static_cast<size_t>(c);
  const Vec3& root = w.capsules[cc][0].a;
  EnvironmentBoxContact e;
  for (size_t k = 0; k < model.environment_boxes.size(); ++k) {
    Aabb bounds = model.environment_box_bounds[k];
    bounds.lo -= Vec3::Constant(kGuardMargin_m);
    bounds.hi += Vec3::Constant(kGuardMargin_m);
    for (int b = 0; b < kJointCount; ++b) {
      if (!w.boxes[cc][static_cast<size_t>(b)].overlaps(bounds)) continue;
      if (!environment_box_contact(w.capsules[cc][static_cast<size_t>(b)], model.environment_boxes[k], root,
                                   -kGuardMargin_m, e) ||
          e.penetration_m > tolerance)
        continue;
      out.push_back({b, e.penetration_m, 0.0, e.normal, e.axis_point});
    }
  }
  if (!model.ground_plane) return;
  for (int b = 0; b < kJointCount; ++b) {
    const Capsule& cap = w.capsules[cc][static_cast<size_t>(b)];
    const Vec3& low = cap.a.y() <= cap.b.y() ? cap.a : cap.b;
    const double depth = cap.radius_m - low.y();
    if (depth > -kGuardMargin_m) out.push_back({b, depth, tolerance, Vec3::UnitY(), low});
  }
}

/// Appends a guard row for every gap that the change dq would take past max(depth, allowed) +
/// kGuardSlack_m (linearised: the depth after is depth - n . J_p dq), while there is room. Returns how many
/// it added.
int add_guard_rows(const BoneTransforms& bones, const PoseChangeVector& dq, std::vector<SurfaceGap>& gaps,
                   RowBlock& J, SmallVector& r) {
  int added = 0;
  for (size_t i = 0; i < gaps.size() && J.rows() < kMaxAllRows; ++i) {
    SurfaceGap& g = gaps[i];
    if (g.guarded) continue;
    const Row row = point_row(bones, g.bone, g.point, g.normal);
    const double after_m = g.depth_m - row.dot(dq);
    const double allowed_m = std::max(g.depth_m, g.allowed_m);
    if (!(after_m > allowed_m + kGuardSlack_m)) continue;
    const Eigen::Index m = J.rows();
    J.conservativeResize(m + 1, Eigen::NoChange);
    r.conservativeResize(m + 1);
    J.row(m) = kGuardRowWeight * row;
    r(m) = kGuardRowWeight * (g.depth_m - allowed_m);
    g.guarded = true;
    ++added;
  }
  return added;
}

/// root += dr; local_j <- R_parent^T exp(w_j) R_parent local_j, R_parent from `bones` (before the change).
void apply_change(const BoneTransforms& bones, const Weights& dq, Pose& pose) {
  pose.root_position_m += dq.head<3>();
  for (int j = 0; j < kJointCount; ++j) {
    const Vec3 w = dq.segment<3>(3 + 3 * j);
    if (w.squaredNorm() < 1e-24) continue;
    const Quat parent =
        j == 0 ? Quat::Identity() : bones[static_cast<size_t>(kJointParent[static_cast<size_t>(j)])].rotation;
    Quat& local = pose.local_rotations[static_cast<size_t>(j)];
    local = (parent.conjugate() * rotation_from_vector(w) * parent * local).normalized();
  }
}

/// Below these counts a loop runs on the calling thread: waking the other worker costs more than the
/// work (about 1 us per pose or pair test, 3 us per solve). Measured at 200 characters: running every
/// loop serially took 1.5 ms, splitting every loop over 2 threads 0.95 ms, these thresholds 0.9 ms.
constexpr size_t kSerialPoses = 64, kSerialPairs = 64, kSerialSolves = 16;
/// Runs f(items[k]) for every k, in parallel when there are enough items to pay for it. Each call
/// writes only its own item's outputs, so the result does not depend on how the work is split.
template <class F>
void for_each_item(const std::vector<int>& items, size_t serial_below, F&& f) {
  if (items.size() < serial_below) {
    for (int item : items) f(item);
    return;
  }
  tbb::parallel_for(size_t{0}, items.size(), [&](size_t k) { f(items[k]); });
}

}  // namespace

void stage_depenetrate(const CorrectorModel& model, CorrectorState& s) {
  const CorrectorParams& p = model.params;
  const size_t pairs = s.body_pairs.size();
  if (p.depenetration_passes <= 0 || s.stats.rejected || (pairs == 0 && model.environment_boxes.empty())) {
    // No pass: no character had its feet's heights solved here (stage_settle_feet reads this list).
    for (int c : s.depenetration.characters) s.depenetration.pairs_of[static_cast<size_t>(c)].clear();
    s.depenetration.characters.clear();
    return;
  }
  const auto nn = static_cast<size_t>(model.characters());
  DepenetrationScratch& w = s.depenetration;
  if (w.bones.size() != nn) {  // first step: size everything once; K^-1 are model constants
    w = DepenetrationScratch{};
    w.bones.resize(nn);
    w.capsules.resize(nn);
    w.boxes.resize(nn);
    w.inverse_weights.resize(nn);
    w.environment.resize(nn);
    w.gaps.resize(nn);
    for (size_t c = 0; c < nn; ++c) w.inverse_weights[c] = inverse_weights(model.bodies[c]);
    w.mine.resize(nn);
    w.pairs_of.resize(nn);
    w.in_list.assign(nn, 0);
    w.moved.assign(nn, 0);
    w.ever_moved.assign(nn, 0);
  }
  if (w.per_pair.size() < pairs) w.per_pair.resize(pairs);
  // Work lists: the characters to (re-)pose and the body pairs to (re-)test. At first every pair with a
  // near capsule pair (narrow phase) and its characters; then the characters the last pass moved and
  // the pairs touching them (a pair whose bodies did not move had no deep contact, or both would have).
  for (int c : w.characters) w.pairs_of[static_cast<size_t>(c)].clear();
  w.characters.clear();
  w.tested.clear();
  for (size_t k = 0; k < pairs; ++k) {
    if (s.per_pair_near[k].empty()) continue;
    w.tested.push_back(static_cast<int>(k));
    for (int c : {s.body_pairs[k].first, s.body_pairs[k].second}) {
      const auto cc = static_cast<size_t>(c);
      if (!w.in_list[cc]) w.characters.push_back(c);
      w.in_list[cc] = 1;
      w.pairs_of[cc].push_back(static_cast<int>(k));
    }
  }
  // Characters near a wall, barrier or stage box are posed and tested against the boxes too (issue 27):
  // the pass pushes bodies sideways, and without the boxes among its rows it pushed them into the
  // corridor's barriers (docs/correction.md).
  if (!model.environment_boxes.empty())
    for (int c = 0; c < model.characters(); ++c)
      if (!w.in_list[static_cast<size_t>(c)] && near_environment(model, s, c, kEnvironmentMargin_m)) {
        w.characters.push_back(c);
        w.in_list[static_cast<size_t>(c)] = 1;
      }
  // w.characters stays as built until the next step, which clears their pairs_of lists.
  std::sort(w.characters.begin(), w.characters.end());
  for (int c : w.characters) w.in_list[static_cast<size_t>(c)] = 0;
  for (int c : w.solved) w.mine[static_cast<size_t>(c)].clear();  // the last step's lists
  w.solved.clear();
  w.changed.clear();
  w.posing = w.characters;
  for (int pass = 0; pass < p.depenetration_passes && !w.posing.empty(); ++pass) {
    for_each_item(w.posing, kSerialPoses, [&](int c) {
      const auto cc = static_cast<size_t>(c);
      w.bones[cc] = forward_kinematics(model.bodies[cc].shape, s.output[cc]);
      w.capsules[cc] = world_capsules(model.bodies[cc].shape, w.bones[cc]);
      for (size_t b = 0; b < kJointCount; ++b) w.boxes[cc][b] = capsule_box(w.capsules[cc][b]);
    });
    // 1-2. Deep contacts per tested pair, with the compliance split.
    for_each_item(w.tested, kSerialPairs, [&](int k) {
      const auto [i, j] = s.body_pairs[static_cast<size_t>(k)];
      find_deep_contacts(w, i, j, s.per_pair_near[static_cast<size_t>(k)], p.depenetration_tolerance_m,
                         w.per_pair[static_cast<size_t>(k)]);
    });
    // Gather per character, in pair order (deterministic).
    for (int c : w.solved) w.mine[static_cast<size_t>(c)].clear();
    w.solved.clear();
    int found = 0;
    for (int k : w.tested)
      for (const DeepContact& d : w.per_pair[static_cast<size_t>(k)]) {
        for (int bone : {d.bone_a, d.bone_b}) {
          mark_touched(s, bone);  // engaged from now on (stage_free_joints.cpp)
          auto& list = w.mine[static_cast<size_t>(bone / kJointCount)];
          if (list.empty()) w.solved.push_back(bone / kJointCount);
          list.push_back(&d);
        }
        ++found;
      }
    if (pass == 0) s.stats.deep_contacts = found;
    // Box contacts of the characters this pass posed (the others did not move since they were last
    // tested), after the pairs' contacts: the gather order stays fixed.
    if (!model.environment_boxes.empty()) {
      for_each_item(w.posing, kSerialPoses, [&](int c) {
        find_environment_contacts(model, w, c, p.depenetration_tolerance_m,
                                  w.environment[static_cast<size_t>(c)]);
      });
      for (int c : w.posing)
        for (const DeepContact& d : w.environment[static_cast<size_t>(c)]) {
          mark_touched(s, d.bone_a);
          auto& list = w.mine[static_cast<size_t>(c)];
          if (list.empty()) w.solved.push_back(c);
          list.push_back(&d);
        }
    }
    // Characters re-posed by this pass whose feet went over budget, or (held_feet_at_input_height) whose
    // held feet stand off their goal heights, are solved too.
    for (int c : w.posing)
      if (w.mine[static_cast<size_t>(c)].empty() &&
          (foot_budget_rows(s, c, p.foot_pop_budget_m, w.bones[static_cast<size_t>(c)]).count > 0 ||
           held_feet_off_height(model, s, c, w.bones[static_cast<size_t>(c)])))
        w.solved.push_back(c);
    if (w.solved.empty()) break;
    ++s.stats.depenetration_passes;
    std::sort(w.solved.begin(), w.solved.end());
    // 3-4. Per character: the least-energy pose change, then held feet re-planted exactly.
    for_each_item(w.solved, kSerialSolves, [&](int c) {
      const auto cc = static_cast<size_t>(c);
      RowBlock J;
      SmallVector r;
      const std::array<Vec3, 2> give_way = held_feet_give_way(s, c, w.mine[cc]);
      constraint_rows(model, s, c, w.bones[cc], w.mine[cc],
                      foot_budget_rows(s, c, p.foot_pop_budget_m, w.bones[cc]), give_way, J, r);
      Weights dq;
      w.moved[cc] = 0;
      // Rate-limited joints (stage_free_joints.cpp) that have used this step's turn take no part; the
      // others turn at most what is left of it, so the pass separates with the joints that may move.
      std::array<double, kJointCount> left{};
      rotation_left(model, s, c, s.output[cc], left);
      Weights inv_w = w.inverse_weights[cc];
      for (int j = 0; j < kJointCount; ++j)
        if (left[static_cast<size_t>(j)] < 1e-3) inv_w.segment<3>(3 + 3 * j).setZero();
      // Engaged knees turn about their hinge freely, off it at most what the rate leaves (issue 27,
      // session 16: the pass had turned held knees sideways, 14-42 deg per flip window).
      std::array<KneeHinge, 2> knees;
      const int hinged = knee_hinges(model, s, c, w.bones[cc], s.output[cc], knees);
      // Held ankles turn about their up axis at most what the rate leaves (issue 27, session 19).
      std::array<AnkleTwist, 2> twists;
      const int twisting = held_ankle_twists(model, s, c, w.bones[cc], s.output[cc], twists);
      const auto solve = [&] {
        if (!(hinged > 0 ? hinged_least_energy_change(J, r, inv_w, knees, hinged, dq)
                         : least_energy_change(J, r, inv_w, dq)))
          return false;
        for (int j = 0; j < kJointCount; ++j) {
          const double angle = dq.segment<3>(3 + 3 * j).norm(), most = left[static_cast<size_t>(j)];
          if (angle > most) dq.segment<3>(3 + 3 * j) *= most / angle;
        }
        return true;
      };
      if (!solve()) return;
      // Surface guards and twist rows: solved again while the change would push a capsule through a box
      // or the ground, or twist a held ankle past the rate.
      std::vector<SurfaceGap>& gaps = w.gaps[cc];
      surface_gaps(model, w, c, p.depenetration_tolerance_m, gaps);
      for (int round = 0; round < kGuardRounds; ++round) {
        const int added = add_guard_rows(w.bones[cc], dq, gaps, J, r);
        if (added + add_twist_rows(twists, twisting, dq, J, r) == 0 || !solve()) break;
      }
      if (!dq.allFinite()) return;
      apply_change(w.bones[cc], dq, s.output[cc]);
      for (int side = 0; side < 2; ++side) {  // the anchors of feet that gave way move with them
        const Vec3& move = give_way[static_cast<size_t>(side)];
        FootHold& hold = s.foot_holds[static_cast<size_t>(2 * c + side)];
        hold.ankle_anchor_m += move;
        hold.ball_anchor_m += move;
        hold.given_way_m += move.norm();
      }
      hold_feet(model, s, c, s.output[cc]);
      w.moved[cc] = 1;
    });
    // Next pass: re-pose the moved characters, re-test the pairs touching them.
    w.posing.clear();
    w.tested.clear();
    for (int c : w.solved) {
      const auto cc = static_cast<size_t>(c);
      if (!w.moved[cc]) continue;
      w.posing.push_back(c);
      if (!w.ever_moved[cc]) w.changed.push_back(c);
      w.ever_moved[cc] = 1;
      for (int k : w.pairs_of[cc]) w.tested.push_back(k);
    }
    std::sort(w.tested.begin(), w.tested.end());
    w.tested.erase(std::unique(w.tested.begin(), w.tested.end()), w.tested.end());
    for (int c : w.solved) w.moved[static_cast<size_t>(c)] = 0;
  }
  // Commit: the next step starts from the depenetrated poses (velocities unchanged, see the header).
  std::sort(w.changed.begin(), w.changed.end());
  for_each_item(w.changed, kSerialPoses, [&](int c) {
    set_bones_from_pose(model, c, s.output[static_cast<size_t>(c)], s.com_m, s.rotation);
  });
  for (int c : w.changed) w.ever_moved[static_cast<size_t>(c)] = 0;
}

}  // namespace crowdlab
