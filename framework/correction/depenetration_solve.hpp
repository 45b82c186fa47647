#pragma once
// The dense least-energy solve of the depenetration pass (stage_depenetrate.cpp), one character at a
// time: the pose change of least control-spring energy meeting a handful of rows (contacts, held feet,
// foot budgets, surface guards), regularised and limited to a trust region; and the same solve with
// engaged knees limited off their hinge (issue 27, session 16) and held ankles' twist bounded (session 19).
// Inputs: the rows J (one per constraint, over dr and w_j), their right-hand sides r (m), the inverse
// control-spring weights K^-1 of the character. Output: dq = [dr (m); w_j (rad, world frame)].
// Method: weighted least norm dq = K^-1 J^T (J K^-1 J^T + eps)^-1 r (e.g. Nocedal & Wright 2006,
// "Numerical Optimization", §16.1 on equality-constrained quadratic programs).
#include <array>

#include <Eigen/Core>

#include "framework/core/forward_kinematics.hpp"
#include "framework/correction/corrector_model.hpp"
#include "framework/correction/corrector_state.hpp"

namespace crowdlab::depenetration {

/// At most this many rows per character and pass (contacts, deepest kept, plus up to 12 held-foot
/// and 4 foot-budget rows), so the dense system stays on the stack; the surface guards below come on
/// top (kMaxGuardRows).
constexpr int kMaxRows = 40;
/// Surface guards (issue 27, session 15): one-sided rows for the environment boxes and the ground.
/// A capsule the pass's change would take deeper than max(d, a), d its depth now (< 0: a gap) and a
/// what the surface allows (0 behind a box face; the pass's tolerance below y = 0, so feet standing on
/// the ground are left alone), gets the row n . J_p [dr; w] = d - max(d, a) and the character is solved
/// again with it: an active set of the inequality n . J_p dq >= d - max(d, a) (the rows are added only
/// where the unconstrained change breaks them, so a capsule may still leave a surface). Without them the pass
/// pushed bodies into the corridor's barriers and swinging feet into the ground while it separated
/// neighbours: of the 28 capsule-frames deeper than 5 mm in a barrier at corridor 6.66 /m^2 (3 s), 16 were
/// not after the Newton step but were after the pass (a pelvis 0 -> 20.8 mm); a swinging foot 19 mm above the
/// ground in the input went 73 mm below it (docs/correction.md, session 15).
constexpr int kMaxGuardRows = 8;
/// Held ankles' twist rows (AnkleTwist): one per leg.
constexpr int kMaxTwistRows = 2;

constexpr int kVariables = kPoseChangeVariables;  // dr, then w_j per joint
using Row = Eigen::Matrix<double, 1, kVariables>;
using Weights = PoseChangeVector;
constexpr int kMaxAllRows = kMaxRows + kMaxGuardRows + kMaxTwistRows;
using RowBlock = Eigen::Matrix<double, Eigen::Dynamic, kVariables, Eigen::RowMajor, kMaxAllRows, kVariables>;
using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxAllRows, kMaxAllRows>;
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxAllRows, 1>;

/// The least-energy pose change meeting the rows (weighted least norm, regularised), then limited: the
/// root moves no farther than the deepest separation asked for, and no joint turns by more than
/// kMaxRotation_rad. Returns false when the solve is not finite.
bool least_energy_change(const RowBlock& J, const SmallVector& r, const Weights& inv_w, Weights& dq);

/// An engaged knee in the pass (params.knee_hinge): its rotation vector in the basis (hinge, two axes
/// off it), the off-hinge part limited to what the rate leaves (knee_off_hinge_left).
struct KneeHinge {
  int joint = 0;
  Mat3 basis = Mat3::Identity();  ///< world axes: the hinge (the thigh's x), then two normal to it
  double left_rad = 0.0;
};

/// Character c's knees limited off their hinge in the pass (at most 2, written to out); returns how many.
int knee_hinges(const CorrectorModel& model, const CorrectorState& s, int c, const BoneTransforms& bones,
                const Pose& pose, std::array<KneeHinge, 2>& out);

/// least_energy_change with the knees' off-hinge turns weighted 0 once their turn is used and limited to
/// what is left otherwise (the knees' columns solved in their hinge bases; the weight is isotropic, so
/// a change of basis leaves the other columns' solution alone).
bool hinged_least_energy_change(const RowBlock& J, const SmallVector& r, const Weights& inv_w,
                                const std::array<KneeHinge, 2>& knees, int count, Weights& dq);

/// A held foot's ankle twist in the pass (params.held_ankle_twist_in_pass; issue 27, session 19). The held
/// foot keeps its world rotation F (hold_feet re-plants it), so a world turn w of the shank (the pelvis',
/// hip's and knee's columns summed) changes the ankle's local rotation S^-1 F by exp(-F^-1 w): its twist
/// about its up axis y by -(F e_y) . w. The pass turned held legs about their long axis to move knees out
/// of contacts, 22-41 deg per flip window of the ankle (session 18's trace). The row bounds the ankle's
/// twist off R_ref = R^_ankle D_old (its last output's deviation on the current input) to the rate:
/// |now + row . dq| <= max(most, |now|), an inequality added where a solve breaks it (as the guards).
/// Measured on the 3 s corridor clip at 6.66 /m^2 (docs/correction.md, session 19): held ankles' twist
/// windows over 20 deg 48 -> 6, flips 144-195 -> 87-114 over three runs, p99 depth within 10 mm.
struct AnkleTwist {
  Row row = Row::Zero();  ///< the twist's change (rad) per unit dq, linearised
  double now_rad = 0.0;   ///< the ankle's twist about y off R_ref in the pose of the pass (signed)
  double most_rad = 0.0;  ///< free_joint_return_radps x h
  bool bounded = false;   ///< its row is in the system
};

/// The twist (rad, in [-pi, pi]) about its y axis of joint j of character c in `pose` off R_ref = R^_j D_old
/// (the last output's deviation on the current input): what the joint turned this step about y.
double twist_off_reference_rad(const CorrectorState& s, int c, int j, const Pose& pose);

/// Character c's held feet whose ankles the rate limits (at most 2, written to out); returns how many.
int held_ankle_twists(const CorrectorModel& model, const CorrectorState& s, int c,
                      const BoneTransforms& bones, const Pose& pose, std::array<AnkleTwist, 2>& out);

/// Appends the row of every ankle twist that dq takes past max(most, |now|) (kTwistSlack_rad), asking for
/// that bound, while there is room. Returns how many it added.
int add_twist_rows(std::array<AnkleTwist, 2>& twists, int count, const Weights& dq, RowBlock& J,
                   SmallVector& r);

}  // namespace crowdlab::depenetration
