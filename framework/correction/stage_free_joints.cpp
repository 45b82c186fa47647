// Free joints (issue 27; ours): the correction changes only what collides.
//
// A study comparing a corrected crowd with its input attributes every difference to resolved
// collisions. The one Newton step of seed 000 Eq. 3 also turns joints that touch nobody: a push on the
// torso swings the arms through their PD springs, the input's own self-contacts (forearms 1-2 cm inside
// the torso) and feet below the floor are pushed out, and every joint lags a little behind a fast
// input. Measured before this stage on gomez2024 (docs/correction.md): joints touching nobody for
// +-0.5 s deviated from their input by up to tens of degrees. Here every joint is either ENGAGED, and
// keeps what the solve gave it, or FREE, and returns to its input:
//
//   touched_c(t)   the bones b of character c whose capsule, at the predicted state of step t, is within
//                  free_joint_margin_m of a capsule of another character (the narrow phase's near list)
//                  or touches an environment box (an environment contact), or that the depenetration
//                  pass separated at step t. The character's own capsules and the ground do not count.
//   engaged_j(t)   touched_c(t') ∩ scope_j ≠ ∅ for some t' in [t - H, t], H = free_joint_hold_s x fps,
//                  scope_j = contact_scope(j) (core/joint_scope.hpp: the bones joint j moves; the whole
//                  body for the pelvis and the legs)
//   release        for a joint that is not engaged, with D_j(t) = R̂_j(t)^-1 R_j(t) its deviation from
//                  the input's local rotation R̂_j:
//                      D_j(t) = slerp(D_j(t-1), I, min(1, ω h / ∠D_j(t-1))),   R_j(t) = R̂_j(t) D_j(t),
//                  i.e. the deviation of the last output turned back toward none at ω =
//                  free_joint_return_radps, whatever the solve gave the joint this step.
//   knee hinge     an engaged knee keeps the flexion about its hinge (x) the solve gave it; what it
//                  turns off the hinge (abduction, and twist about the shank) is limited to the same rate
//                  (limit_off_hinge; issue 27, session 16; with knee_hinge false only the twist about the
//                  shank, limit_twist, session 11). The depenetration pass turns engaged knees off their
//                  hinge at most by what the rate leaves (knee_off_hinge_left). With lift_off_knees
//                  (session 17, off by default) the knee of a leg whose foot is not held, more than 3
//                  rate turns off the input, is limited whole, as the joints of the set.
// It runs after the projection and before the foot holds (stage_integrate), so held feet are still
// re-planted; the bones are rebuilt from the released pose, so the next step starts from it and its
// velocities are those of the released motion (a stronger PD pull in the limit: the free joint follows
// its input exactly). The free-limb measure (metrics/free_limb_deviation.hpp) uses the same scopes.
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
namespace {

/// Steps a joint stays engaged after its scope was last touched.
std::int64_t hold_steps(const CorrectorModel& model) {
  return static_cast<std::int64_t>(std::lround(model.params.free_joint_hold_s / model.h));
}

/// Engages, until step + hold, every joint of c whose scope meets the touched bones.
void engage(const CorrectorModel& model, CorrectorState& s, int c) {
  const BoneMask touched = s.touched[static_cast<size_t>(c)];
  if (touched == 0) return;
  const std::int64_t until = s.step_index + hold_steps(model);
  for (int j = 0; j < kJointCount; ++j)
    if (touched & kContactScopes[static_cast<size_t>(j)])
      s.engaged_until[static_cast<size_t>(c * kJointCount + j)] = until;
}

/// Whether joint j's engaged deviation is rate-limited (params.rate_limited_joints).
/// Measured on gomez2024 at 6.66 /m^2 (3 s) without a limit: of 11,467 flips in the corridor, 7,774
/// were hands, 2,204 wrists, 1,177 balls, 218 ankles, 41 elbows; limiting every joint instead left p99
/// inter-body depths of 20-21 mm (the trunk and the legs could no longer get out of the way), limiting
/// the elbows too 11-17 mm in the stationary crowd (session 9; since session 13 the elbows are limited at
/// no cost in depth, docs/correction.md).
bool limited(const CorrectorModel& model, int j) {
  return (model.params.rate_limited_joints & (BoneMask{1} << j)) != 0;
}

/// The knees, whose engaged twist (about the shank) is rate-limited when their ankles are
/// (params.rate_limited_joints) and they are not. The twist of a shank moves no
/// capsule of the leg (a capsule is symmetric about its axis; the held foot keeps its own rotation), so
/// limiting it costs no separation; without the limit the solve and the pass turned knees of held legs
/// by 10-16 deg per frame about the shank, and their ankles the other way (issue 27: the corridor's
/// knee and ankle flips).
int twist_limited_child(int j) {
  switch (j) {
    case kLeftKnee:
      return kLeftAnkle;
    case kRightKnee:
      return kRightAnkle;
    default:
      return -1;
  }
}

/// Whether joint j of character c turns at most the rate while engaged: a joint of
/// params.rate_limited_joints, or (params.lift_off_knees; issue 27, session 17) the knee of a leg whose
/// foot is not held, whose flexion no leg IK sets. Without it a knee whose held leg the stance had kept
/// 15-37 deg straighter than the input's turned back by 13-24 deg within 3 frames of the lift-off.
bool limited_now(const CorrectorModel& model, const CorrectorState& s, int c, int j) {
  if (limited(model, j)) return true;
  if (!model.params.lift_off_knees || (j != kLeftKnee && j != kRightKnee)) return false;
  const auto f = static_cast<size_t>(2 * c + (j == kLeftKnee ? 0 : 1));
  if (f >= s.foot_holds.size() || s.foot_holds[f].held()) return false;
  // Only while it returns from a deviation that a turn back within 3 frames would flip: a swinging knee
  // near its input still gets out of the way freely (limited always, the standing crowd's p99 depth at
  // 6.66 /m^2 rose 8.5 -> 11.1 mm).
  return knee_flexion_off_input_rad(s, c, j) > 3.0 * model.params.free_joint_return_radps * model.h;
}

}  // namespace

double knee_flexion_twist_off_input_rad(const CorrectorState& s, int c, int knee) {
  const auto g = static_cast<size_t>(c * kJointCount + knee);
  if (g >= s.output_deviation.size()) return 0.0;  // no output yet
  const Quat& d = s.output_deviation[g];
  return 2.0 * std::atan2(d.x(), d.w());
}

double knee_flexion_off_input_rad(const CorrectorState& s, int c, int knee) {
  return std::abs(knee_flexion_twist_off_input_rad(s, c, knee));
}

Quat off_hinge_part(const Quat& change) {
  // Swing-twist decomposition about x (e.g. Dobrowolski 2015, "Swing-twist decomposition in Clifford
  // algebra", arXiv:1506.05481): the twist keeps w and the x component.
  const double norm = std::hypot(change.w(), change.x());
  if (norm < 1e-12) return change;  // a half turn off the hinge: all of it is off
  const Quat hinge(change.w() / norm, change.x() / norm, 0.0, 0.0);
  return (change * hinge.conjugate()).normalized();
}

Quat limit_off_hinge(const Quat& from, const Quat& to, double max_turn_rad) {
  const Quat change = (to * from.conjugate()).normalized();
  const Quat off = off_hinge_part(change);
  const double angle = off.angularDistance(Quat::Identity());
  if (!(angle > max_turn_rad)) return to;
  const Quat hinge = (off.conjugate() * change).normalized();
  return (Quat::Identity().slerp(max_turn_rad / angle, off) * hinge * from).normalized();
}

Quat limit_twist(const Quat& from, const Quat& to, const Vec3& axis, double max_turn_rad) {
  const Quat change = (from.conjugate() * to).normalized();
  const double along = change.vec().dot(axis);
  const double norm = std::hypot(change.w(), along);
  if (norm < 1e-12) return to;  // a half turn of swing: no twist to speak of
  Quat twist(change.w() / norm, along * axis.x() / norm, along * axis.y() / norm, along * axis.z() / norm);
  const double angle = twist.angularDistance(Quat::Identity());
  if (!(angle > max_turn_rad)) return to;
  const Quat swing = (change * twist.conjugate()).normalized();
  twist = Quat::Identity().slerp(max_turn_rad / angle, twist);
  return (from * swing * twist).normalized();
}

void mark_touched(CorrectorState& s, int global_bone) {
  s.touched[static_cast<size_t>(global_bone / kJointCount)] |= BoneMask{1} << (global_bone % kJointCount);
}

void stage_contact_scope(const CorrectorModel& model, CorrectorState& s) {
  std::fill(s.touched.begin(), s.touched.end(), BoneMask{0});
  if (!model.params.release_free_joints) return;
  // The narrow phase tested every near capsule pair against free_joint_margin_m (pair_touched): it
  // computes their distances anyway, in parallel over pairs (stage_narrow_phase.cpp).
  const size_t pairs = s.body_pairs.size();
  for (size_t k = 0; k < pairs; ++k) {
    s.touched[static_cast<size_t>(s.body_pairs[k].first)] |= s.pair_touched[k][0];
    s.touched[static_cast<size_t>(s.body_pairs[k].second)] |= s.pair_touched[k][1];
  }
  for (const Contact& c : s.contacts)
    if (c.kind == ContactKind::kEnvironment || c.kind == ContactKind::kInterBody) {
      mark_touched(s, c.bone_a);
      if (c.kind == ContactKind::kInterBody) mark_touched(s, c.bone_b);
    }
  for (int c = 0; c < model.characters(); ++c) engage(model, s, c);
}

bool release_free_joints(const CorrectorModel& model, const CorrectorState& s, int c, Pose& pose) {
  if (!model.params.release_free_joints) return false;
  const double step = model.params.free_joint_return_radps * model.h;
  const Pose& target = s.target[static_cast<size_t>(c)];
  bool changed = false;
  for (int j = 0; j < kJointCount; ++j) {
    const auto g = static_cast<size_t>(c * kJointCount + j);
    const auto jj = static_cast<size_t>(j);
    const Quat& d_old = s.output_deviation[g];
    // Free: back toward no deviation; engaged: toward what the solve (and the pass) gave it.
    const bool engaged = s.step_index <= s.engaged_until[g];
    const Quat want = engaged
                          ? (target.local_rotations[jj].conjugate() * pose.local_rotations[jj]).normalized()
                          : Quat::Identity();
    const double angle = 2.0 * std::acos(std::min(1.0, std::abs(d_old.dot(want))));
    // Engaged joints outside params.rate_limited_joints follow the solve at any rate (they carry the
    // pushes); the limited ones turn at most the rate.
    if (engaged && !limited_now(model, s, c, j)) {
      const int child = twist_limited_child(j);
      if (child < 0 || !limited(model, child)) continue;
      if (model.params.knee_hinge) {  // issue 27, session 16: all but the flexion limited
        const Quat from = (target.local_rotations[jj] * d_old).normalized();
        const Quat next = limit_off_hinge(from, pose.local_rotations[jj], step);
        if (std::abs(next.dot(pose.local_rotations[jj])) >= 1.0 - 1e-12) continue;
        pose.local_rotations[jj] = next;
        changed = true;
        continue;
      }
      const Vec3 axis =
          model.bodies[static_cast<size_t>(c)].shape.joint_offsets_m[static_cast<size_t>(child)].normalized();
      const Quat d = limit_twist(d_old, want, axis, step);
      if (std::abs(d.dot(want)) >= 1.0 - 1e-12) continue;
      pose.local_rotations[jj] = (target.local_rotations[jj] * d).normalized();
      changed = true;
      continue;
    }
    if (engaged && angle <= step) continue;
    const Quat d = angle <= step ? want : d_old.slerp(step / angle, want);
    const Quat next = (target.local_rotations[jj] * d).normalized();
    if (std::abs(next.dot(pose.local_rotations[jj])) < 1.0 - 1e-12) changed = true;
    pose.local_rotations[jj] = next;
  }
  return changed;
}

void rotation_left(const CorrectorModel& model, const CorrectorState& s, int c, const Pose& pose,
                   std::array<double, kJointCount>& left) {
  const double step = model.params.free_joint_return_radps * model.h;
  const Pose& target = s.target[static_cast<size_t>(c)];
  for (int j = 0; j < kJointCount; ++j) {
    const auto g = static_cast<size_t>(c * kJointCount + j);
    const auto jj = static_cast<size_t>(j);
    if (!model.params.release_free_joints ||
        (s.step_index <= s.engaged_until[g] && !limited_now(model, s, c, j))) {
      left[jj] = std::numeric_limits<double>::infinity();
      continue;
    }
    if (s.step_index > s.engaged_until[g]) {
      left[jj] = 0.0;
      continue;
    }
    const Quat d = (target.local_rotations[jj].conjugate() * pose.local_rotations[jj]).normalized();
    const double used = 2.0 * std::acos(std::min(1.0, std::abs(s.output_deviation[g].dot(d))));
    left[jj] = std::max(0.0, step - used);
  }
}

double knee_off_hinge_left(const CorrectorModel& model, const CorrectorState& s, int c, const Pose& pose,
                           int knee) {
  const int ankle = twist_limited_child(knee);
  const auto g = static_cast<size_t>(c * kJointCount + knee);
  const auto kj = static_cast<size_t>(knee);
  if (!model.params.release_free_joints || !model.params.knee_hinge || ankle < 0 ||
      limited_now(model, s, c, knee) || !limited(model, ankle) || s.step_index > s.engaged_until[g])
    return -1.0;
  const Quat from =
      (s.target[static_cast<size_t>(c)].local_rotations[kj] * s.output_deviation[g]).normalized();
  const double used = off_hinge_part((pose.local_rotations[kj] * from.conjugate()).normalized())
                          .angularDistance(Quat::Identity());
  return std::max(0.0, model.params.free_joint_return_radps * model.h - used);
}

void stage_record_deviation(const CorrectorModel& model, CorrectorState& s) {
  if (!model.params.release_free_joints) return;
  // Per character in parallel: each call writes only character c's slots (engaged_until, output,
  // foot holds, bones, output_deviation). It had been serial as "~24 quaternion products per character",
  // but a released joint costs a leg IK and a forward kinematics as well: 0.07-0.13 ms of the
  // 60-character step, serial (session 20).
  tbb::parallel_for(0, model.characters(), [&](int c) {
    engage(model, s, c);  // the bones the depenetration pass moved apart this step
    const auto cc = static_cast<size_t>(c);
    // The pass may have turned joints faster than the rate: limit again, re-plant held feet, and start
    // the next step from that pose (a rejected step keeps its last stable state as it is).
    if (!s.stats.rejected && release_free_joints(model, s, c, s.output[cc])) {
      hold_feet(model, s, c, s.output[cc]);
      set_bones_from_pose(model, c, s.output[cc], s.com_m, s.rotation);
    }
    for (size_t j = 0; j < kJointCount; ++j)
      s.output_deviation[cc * kJointCount + j] =
          (s.target[cc].local_rotations[j].conjugate() * s.output[cc].local_rotations[j]).normalized();
  });
}

}  // namespace crowdlab
