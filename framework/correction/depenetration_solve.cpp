// The dense least-energy solve of the depenetration pass: see depenetration_solve.hpp.
#include "framework/correction/depenetration_solve.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "framework/correction/corrector_step.hpp"

namespace crowdlab::depenetration {
namespace {

/// Largest rotation one pass may give a joint (rad). The pass linearises every point as w x (p - o),
/// whose error grows as |p - o| |w|^2 / 2; 0.2 rad keeps it below 10 % of the move. Measured in an
/// earlier variant (every pair re-tested, corridor at 6.66 /m^2, 4 s, 6 passes): 0.1 rad left more
/// depth, 0.4 rad the same as 0.2 (p99 13.2 vs 13.4 mm).
constexpr double kMaxRotation_rad = 0.2;
/// Relative Tikhonov term on the constraint system (times its largest diagonal entry): rows that
/// conflict (a limb pressed from two sides, a contact against a held foot) get a least-squares
/// compromise instead of an exploding solve. At 1e-6 nearly dependent rows threw a pelvis 40 cm in one
/// step; 1e-4 left p99 56 mm where 1e-2 left 16 mm (stationary 5.55 /m^2, 3 passes of 0.1 rad); 1e-3
/// with 6 passes of 0.2 rad left 7.4 mm there and 7.5 mm in the corridor at 3.33 /m^2.
constexpr double kRegularisation = 1e-3;
/// Scale of the ankle twist rows (m per rad): a rotation row's entries are 1 where a point row's are lever
/// arms; scaled so, it weighs as a guard row (kGuardRowWeight 10, stage_depenetrate.cpp) on a point 10 cm
/// from the axis: where it conflicts with a contact it mostly wins. The only value measured (session 19).
constexpr double kTwistRowScale_m = 1.0;
/// A twist row is added when the change would take the ankle this far (rad) past its bound.
constexpr double kTwistSlack_rad = 1e-3;

}  // namespace

/// The least-energy pose change meeting the rows (weighted least norm, regularised), then limited: the
/// root moves no farther than the deepest separation asked for, and no joint turns by more than
/// kMaxRotation_rad. Returns false when the solve is not finite.
bool least_energy_change(const RowBlock& J, const SmallVector& r, const Weights& inv_w, Weights& dq) {
  const Eigen::Index m = J.rows();
  const RowBlock JW = J * inv_w.asDiagonal();
  // Coefficient-wise products: for a few rows Eigen's blocked GEMM path costs more than the arithmetic.
  SmallMatrix A = JW.lazyProduct(J.transpose());
  double largest = 0.0, wanted = 0.0;  // largest diagonal entry, deepest separation asked for
  for (Eigen::Index i = 0; i < m; ++i) {
    largest = std::max(largest, A(i, i));
    wanted = std::max(wanted, std::abs(r(i)));
  }
  A.diagonal().array() += kRegularisation * largest;
  const SmallVector y = A.ldlt().solve(r);
  dq = JW.transpose().lazyProduct(y);
  if (!dq.allFinite()) return false;
  // Trust region: the root moves no farther than the deepest separation asked for, and each joint
  // turns by at most kMaxRotation_rad (the rest is left to the next pass, re-linearised).
  const double root_move = dq.head<3>().norm();
  if (root_move > wanted) dq.head<3>() *= wanted / root_move;
  for (int j = 0; j < kJointCount; ++j) {
    const double angle = dq.segment<3>(3 + 3 * j).norm();
    if (angle > kMaxRotation_rad) dq.segment<3>(3 + 3 * j) *= kMaxRotation_rad / angle;
  }
  return true;
}

/// Character c's knees limited off their hinge in the pass (at most 2, written to out); returns how many.
int knee_hinges(const CorrectorModel& model, const CorrectorState& s, int c, const BoneTransforms& bones,
                const Pose& pose, std::array<KneeHinge, 2>& out) {
  int n = 0;
  for (const int knee : {kLeftKnee, kRightKnee}) {
    const double left = knee_off_hinge_left(model, s, c, pose, knee);
    if (left < 0.0) continue;
    KneeHinge& k = out[static_cast<size_t>(n++)];
    k.joint = knee;
    k.left_rad = left;
    const Vec3 hinge =
        bones[static_cast<size_t>(kJointParent[static_cast<size_t>(knee)])].rotation * Vec3::UnitX();
    k.basis.col(0) = hinge;
    k.basis.col(1) = hinge.unitOrthogonal();
    k.basis.col(2) = hinge.cross(k.basis.col(1));
  }
  return n;
}

/// least_energy_change with the knees' off-hinge turns weighted 0 once their turn is used and limited to
/// what is left otherwise (the knees' columns solved in their hinge bases; the weight is isotropic, so
/// a change of basis leaves the other columns' solution alone).
bool hinged_least_energy_change(const RowBlock& J, const SmallVector& r, const Weights& inv_w,
                                const std::array<KneeHinge, 2>& knees, int count, Weights& dq) {
  RowBlock Jt = J;
  Weights inv_t = inv_w;
  for (int k = 0; k < count; ++k) {
    const KneeHinge& knee = knees[static_cast<size_t>(k)];
    const int col = 3 + 3 * knee.joint;
    Jt.middleCols<3>(col) = J.middleCols<3>(col) * knee.basis;
    if (knee.left_rad < 1e-3) inv_t.segment<2>(col + 1).setZero();
  }
  if (!least_energy_change(Jt, r, inv_t, dq)) return false;
  for (int k = 0; k < count; ++k) {
    const KneeHinge& knee = knees[static_cast<size_t>(k)];
    const int col = 3 + 3 * knee.joint;
    Vec3 w = dq.segment<3>(col);
    const double off = w.tail<2>().norm();
    if (off > knee.left_rad) w.tail<2>() *= knee.left_rad / off;
    dq.segment<3>(col) = knee.basis * w;
  }
  return true;
}

double twist_off_reference_rad(const CorrectorState& s, int c, int j, const Pose& pose) {
  const auto jj = static_cast<size_t>(j), g = static_cast<size_t>(c * kJointCount + j);
  if (g >= s.output_deviation.size()) return 0.0;
  const Quat ref =
      (s.target[static_cast<size_t>(c)].local_rotations[jj] * s.output_deviation[g]).normalized();
  Quat change = (ref.conjugate() * pose.local_rotations[jj]).normalized();
  if (change.w() < 0.0) change.coeffs() = -change.coeffs();  // the same rotation; its twist in [-pi, pi]
  return 2.0 * std::atan2(change.y(), change.w());
}

int held_ankle_twists(const CorrectorModel& model, const CorrectorState& s, int c,
                      const BoneTransforms& bones, const Pose& pose, std::array<AnkleTwist, 2>& out) {
  const CorrectorParams& p = model.params;
  if (!p.held_ankle_twist_in_pass || !p.release_free_joints) return 0;
  int n = 0;
  for (int side = 0; side < 2; ++side) {
    const LegJoints lj = leg_joints(kLegSides[side]);
    const auto g = static_cast<size_t>(c * kJointCount + lj.ankle);
    if (!s.foot_holds[static_cast<size_t>(2 * c + side)].held() ||
        (p.rate_limited_joints & (BoneMask{1} << lj.ankle)) == 0 || g >= s.output_deviation.size())
      continue;
    const auto aj = static_cast<size_t>(lj.ankle);
    AnkleTwist& t = out[static_cast<size_t>(n++)];
    t = AnkleTwist{};
    t.now_rad = twist_off_reference_rad(s, c, lj.ankle, pose);
    t.most_rad = p.free_joint_return_radps * model.h;
    const Vec3 up = bones[aj].rotation * Vec3::UnitY();
    for (int j = kJointParent[aj]; j >= 0; j = kJointParent[static_cast<size_t>(j)])
      t.row.segment<3>(3 + 3 * j) = -up.transpose();
  }
  return n;
}

int add_twist_rows(std::array<AnkleTwist, 2>& twists, int count, const Weights& dq, RowBlock& J,
                   SmallVector& r) {
  int added = 0;
  for (int k = 0; k < count && J.rows() < kMaxAllRows; ++k) {
    AnkleTwist& t = twists[static_cast<size_t>(k)];
    if (t.bounded) continue;
    const double after = t.now_rad + t.row.dot(dq), bound = std::max(t.most_rad, std::abs(t.now_rad));
    if (!(std::abs(after) > bound + kTwistSlack_rad)) continue;
    const Eigen::Index m = J.rows();
    J.conservativeResize(m + 1, Eigen::NoChange);
    r.conservativeResize(m + 1);
    J.row(m) = kTwistRowScale_m * t.row;
    r(m) = kTwistRowScale_m * (std::copysign(bound, after) - t.now_rad);
    t.bounded = true;
    ++added;
  }
  return added;
}

}  // namespace crowdlab::depenetration
