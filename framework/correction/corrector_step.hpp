#pragma once
// One time step of the collision-correction solver (seed 000 Eq. 3, backward Euler as an
// optimisation, one Newton iteration), as named stages run in this order:
//
//   stage_targets           validate the input poses, initialise the state on the first step,
//                           update which feet the input plants (foot holds)
//   stage_assemble          gradient and PSD (Gauss-Newton) Hessian of E_inertia + E_gravity +
//                           E_joints + E_control at the start-of-step state (the tree part T, b)
//   stage_predict           exact per-character tree solve T dq_free = b: where every body would be
//                           at the end of the step if nothing touched it
//   stage_broad_phase       world capsules at that predicted state, body AABBs, sweep -> body pairs
//   stage_narrow_phase      bounding spheres -> exact capsule-capsule / ground / environment contacts
//   stage_contact_scope     which bones are within free_joint_margin_m of another character (tested
//                           by the narrow phase) or the environment; which joints stay engaged
//                           (stage_free_joints.cpp)
//   stage_assemble_contacts E_collisions linearised at the predicted state (rows w, depth0)
//   stage_solve             per-character tree factorisation with contact blocks (preconditioner) +
//                           PCG warm-started at dq_free; pulling contacts removed (active set)
//   stage_integrate         apply the increment, project to joint rotations + root position,
//                           return free joints to their input (stage_free_joints.cpp), re-plant held
//                           feet by leg IK, commit
//   stage_depenetrate       push apart the inter-body capsule pairs the step left deeper than a
//                           tolerance, by least-energy pose changes (stage_depenetrate.cpp)
//   stage_record_deviation  every joint's deviation of the output from its input, for the next release
//   stage_settle_feet       the root moved vertically so that held feet stand at the input's height
//                           (stage_settle_feet.cpp)
//
// Why contacts are found at the predicted state (ours; the paper does not say where its one Newton
// iteration finds its contacts): contacts found at the start-of-step state miss every contact that a
// limb runs into during the step. A dancer's hand moves 5-10 cm per frame at 30 fps, so those
// contacts start deep and are pushed out one frame late. Detecting at the contact-free end-of-step
// state is the "speculative contact" idea of game physics (Catto, GDC 2013 "Continuous collision")
// applied to the penalty formulation: a Newton step whose linearisation point for E_collisions is the
// contact-free prediction, which for the untouched parts of every body is the exact solution.
//
// Every stage computes from the state left by the previous one and writes only its own arrays; work
// is split across characters (TBB) with per-index output slots and fixed-order reductions, so the
// result is bit-identical for any thread count.
#include <array>
#include <vector>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/pose.hpp"
#include "framework/correction/corrector_model.hpp"
#include "framework/correction/corrector_state.hpp"

namespace crowdlab {

/// Runs all stages; returns the corrected poses (also in state.output). Throws InputError for a
/// wrong number of targets or an invalid pose. A step whose solve diverges is rejected: the state
/// keeps its last stable value (velocities zeroed) and state.stats.rejected is set.
const std::vector<Pose>& corrector_step(const CorrectorModel& model, CorrectorState& state,
                                        const std::vector<Pose>& targets);

void stage_targets(const CorrectorModel& model, CorrectorState& state, const std::vector<Pose>& targets);
void stage_assemble(const CorrectorModel& model, CorrectorState& state);
void stage_predict(const CorrectorModel& model, CorrectorState& state);
void stage_broad_phase(const CorrectorModel& model, CorrectorState& state);
void stage_narrow_phase(const CorrectorModel& model, CorrectorState& state);
void stage_assemble_contacts(const CorrectorModel& model, CorrectorState& state);
void stage_solve(const CorrectorModel& model, CorrectorState& state);
void stage_integrate(const CorrectorModel& model, CorrectorState& state);
void stage_depenetrate(const CorrectorModel& model, CorrectorState& state);
void stage_contact_scope(const CorrectorModel& model, CorrectorState& state);
void stage_record_deviation(const CorrectorModel& model, CorrectorState& state);
void stage_settle_feet(const CorrectorModel& model, CorrectorState& state);
/// How far (m, + up) to move the root of a character whose held feet (held: left, right) are error_m
/// above their goal heights: the one held foot's error, or both feet's smaller one when they agree in
/// sign, 0 when one floats and the other sinks (stage_settle_feet.cpp).
double held_feet_settle_m(const std::array<bool, 2>& held, const std::array<double, 2>& error_m);
/// The height error (m) of side's held foot in `bones`: its held joint's height minus its goal's
/// (foot_goal; the ankle when it is held, else the ball of a rolling foot).
double held_height_error_m(const CorrectorModel& model, const CorrectorState& state, int c, int side,
                           const BoneTransforms& bones);
/// Moves character c's root vertically so that its held feet stand at their goal heights
/// (held_feet_settle_m, at most foot_pop_budget_m, never lowering a swinging foot into the ground).
/// Returns whether the pose changed.
bool settle_held_feet(const CorrectorModel& model, const CorrectorState& state, int c, Pose& pose);

/// How far (rad) character c's knee bends off the input's flexion in its last output, signed: the twist of
/// its output deviation about the hinge axis x, in (-2 pi, 2 pi] (lift_off_knees; issue 27, sessions
/// 17-18). 0 before the first output.
double knee_flexion_twist_off_input_rad(const CorrectorState& state, int c, int knee);
/// Its magnitude (rad, >= 0).
double knee_flexion_off_input_rad(const CorrectorState& state, int c, int knee);

/// Free joints (stage_free_joints.cpp): in character c's projected pose, every joint that is not
/// engaged turns back toward its input rotation, and every engaged one toward the pose's, each at most
/// params.free_joint_return_radps away from the last output's deviation. Returns whether the rate
/// limit changed an engaged joint.
bool release_free_joints(const CorrectorModel& model, const CorrectorState& state, int c, Pose& pose);
/// The rotation `to` with its twist about `axis` (unit, in the frame the rotations act on from the right)
/// relative to `from` limited to max_turn_rad: from * swing * twist, twist turned back toward none.
Quat limit_twist(const Quat& from, const Quat& to, const Vec3& axis, double max_turn_rad);
/// The part of a rotation change (acting from the left, in a knee's parent frame) that is not about the
/// knee's hinge, the x axis: change = off_hinge_part(change) * (a turn about x).
Quat off_hinge_part(const Quat& change);
/// The rotation `to` with its turn off the hinge relative to `from` (off_hinge_part of to from^-1) limited
/// to max_turn_rad; its turn about the hinge kept whole.
Quat limit_off_hinge(const Quat& from, const Quat& to, double max_turn_rad);
/// What is left (rad) of the rate limit's turn off the hinge for knee `knee` of character c in `pose`
/// (params.knee_hinge, an engaged knee whose ankle is rate-limited); -1 where the knee is not so limited.
double knee_off_hinge_left(const CorrectorModel& model, const CorrectorState& state, int c, const Pose& pose,
                           int knee);
/// How much more (rad) each joint of character c may turn this step: what the rate limit of
/// stage_free_joints.cpp leaves of it from the last output's deviation to `pose`'s (infinite for the joints
/// it does not limit, 0 for free joints).
void rotation_left(const CorrectorModel& model, const CorrectorState& state, int c, const Pose& pose,
                   std::array<double, kJointCount>& left);
/// Marks bones of character c in contact this step (the depenetration pass's deep contacts).
void mark_touched(CorrectorState& state, int global_bone);

/// Character c's contact terms: precond = tree diagonal + sum of k w w^T over its contacts, rhs =
/// rhs_tree - sum of k depth0 w (contacts with stiffness 0 skipped). Used by stage_assemble_contacts
/// and by the active set of stage_solve.
void assemble_character_contacts(CorrectorState& state, int c);

/// Foot holds (stage_foot_holds.cpp). update_foot_holds runs in stage_targets once character c's
/// target joints are updated (old_target_foot_rotation: the input's left/right ankle-bone rotations
/// at the previous step); hold_feet re-plants c's held feet in its projected pose (stage_integrate and
/// the depenetration pass), then lifts feet below the input's ground (keep_feet_above_ground).
void update_foot_holds(const CorrectorModel& model, CorrectorState& state, int c,
                       const std::array<Quat, 2>& old_target_foot_rotation);
void hold_feet(const CorrectorModel& model, CorrectorState& state, int c, Pose& pose);
/// Lowest point (m) of one foot's capsules (its ankle and ball bones).
double foot_sole_height_m(const WorldCapsules& capsules, const LegJoints& leg);
/// With params.feet_above_input_ground, lifts each foot of character c whose sole in `pose` lies more
/// than 5 mm (and foot_hold_tolerance_m) below min(0, its sole in the input's pose) back to 5 mm below it
/// by the least-change leg IK, the foot's world rotation kept (run by hold_feet). Returns how many feet
/// it lifted.
int keep_feet_above_ground(const CorrectorModel& model, const CorrectorState& state, int c, Pose& pose);
/// Where a held foot of character c (side 0 left, 1 right) must be: ankle and ball joints (world, m)
/// and the ankle bone's world rotation. Also the goal of the feet's world springs in the solve.
struct FootGoal {
  Vec3 ankle_m = Vec3::Zero(), ball_m = Vec3::Zero();
  Quat rotation = Quat::Identity();
};
/// A held foot's rotation offset (world, output = offset * input) with its tilt turned back toward 0 by
/// at most max_turn_rad: offset = swing * twist, twist about the world vertical (+Y), swing returned
/// toward the identity (stage_foot_holds.cpp).
Quat return_foot_tilt(const Quat& offset, double max_turn_rad);
FootGoal foot_goal(const CorrectorModel& model, const CorrectorState& state, int c, int side);
/// Stores character c's foot joint positions of the current bone state (the last output) in
/// state.foot_start_m, before the step moves them (stage_targets).
void record_foot_start(const CorrectorModel& model, CorrectorState& state, int c);

/// The unit quaternion of a rotation vector (axis * angle).
Quat rotation_from_vector(const Vec3& v);

/// The rotation vector (axis * angle, angle in [-pi, pi]) of a unit quaternion.
Vec3 rotation_vector(const Quat& q);

/// World position of bone g's frame origin (its joint), from the COM state.
inline Vec3 bone_origin(const CorrectorModel& model, const CorrectorState& state, int g) {
  const auto& body = model.bodies[static_cast<size_t>(g / kJointCount)];
  return state.com_m[static_cast<size_t>(g)] -
         state.rotation[static_cast<size_t>(g)] * body.com_local_m[static_cast<size_t>(g % kJointCount)];
}

/// Sets the bone states of character c from a pose (forward kinematics), velocities untouched.
void set_bones_from_pose(const CorrectorModel& model, int c, const Pose& pose, std::vector<Vec3>& com,
                         std::vector<Quat>& rotation);

/// The pose of character c read back from its bone states (root position = bone 0's origin,
/// local rotations = parent^-1 * child): the projection of seed 000 §3.2.
Pose pose_from_bones(const CorrectorModel& model, int c, const std::vector<Vec3>& com,
                     const std::vector<Quat>& rotation);

}  // namespace crowdlab
