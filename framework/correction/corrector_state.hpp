#pragma once
// CorrectorState: the mutable half of the solver (MuJoCo-style mjData). Sized once by
// make_corrector_state(); the step reuses every array, so the per-step loop does not allocate once
// the contact buffers have grown to their working size.
//
// Index conventions: bone arrays have model.bones() = 24 N entries, bone b of character c at c*24+b.
// Frames/units: world frame (Y up), metres, seconds, radians. Generalised increments per bone are
// Vec6 = (dx of the COM in m, dtheta in rad as a world-frame rotation vector).
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/joint_scope.hpp"
#include "framework/core/pose.hpp"
#include "framework/correction/corrector_model.hpp"

namespace crowdlab {

enum class ContactKind : std::uint8_t { kInterBody, kIntraBody, kGround, kEnvironment };

/// One penalty contact, linearised (seed 000 §3.4: E = 1/2 k delta^2 on the penetration depth).
/// It is found at the contact-free predicted state q_old + dq_free (stage_predict) and linearised
/// there: delta(dq) ~= depth + w_a . (dq_a - dq_free_a) + w_b . (dq_b - dq_free_b)
///                   = depth0 + w_a . dq_a + w_b . dq_b,
/// so the Gauss-Newton Hessian is k w w^T (PSD).
struct Contact {
  int bone_a = -1;              ///< global bone index
  int bone_b = -1;              ///< global bone index, or -1 for ground / environment (static side)
  double depth_m = 0.0;         ///< penetration depth (+ offset) at the predicted state (> 0)
  double depth0 = 0.0;          ///< linearised depth at dq = 0 (filled by the assemble stage)
  double stiffness = 0.0;       ///< k (N/m)
  Vec3 normal = Vec3::UnitY();  ///< unit, from b (or the static side) toward a
  Vec3 point_a = Vec3::Zero();  ///< contact point on a's capsule axis (world, m)
  Vec3 point_b = Vec3::Zero();  ///< contact point on b's capsule axis (world, m); unused if static
  Vec6 w_a = Vec6::Zero();      ///< d delta / d dq_a (filled by the assemble stage)
  Vec6 w_b = Vec6::Zero();      ///< d delta / d dq_b
  ContactKind kind = ContactKind::kInterBody;
};

/// The structured coupling block H[child, parent] of one soft joint plus its Eq. 4 control term
/// (see tree_factor.hpp): H[c,p] = -joint_k a_c^T a_p - rot_k [0 0; 0 I3], a_x = [I3, -[arm_x]x].
struct JointCoupling {
  Vec3 arm_child = Vec3::Zero();   ///< joint point - child COM (world, m)
  Vec3 arm_parent = Vec3::Zero();  ///< joint attachment point - parent COM (world, m)
  double joint_k = 0.0;            ///< soft joint spring (N/m)
  double rot_k = 0.0;              ///< 2 (k + d/h^2) of Eq. 4 (N m / rad)
};

/// Per-step statistics (also what the benchmark prints).
struct StepStats {
  int inter_body_contacts = 0;
  int intra_body_contacts = 0;
  int ground_contacts = 0;
  int environment_contacts = 0;
  int body_pairs = 0;  ///< character pairs surviving the AABB cull
  int cg_iterations = 0;
  double cg_relative_residual = 0.0;
  bool converged = true;           ///< CG met its tolerance
  bool rejected = false;           ///< the step was discarded and the last stable state kept
  double max_penetration_m = 0.0;  ///< deepest inter-body contact (+ offset) at the predicted state
  int pulling_contacts = 0;   ///< contacts whose linearised depth ends negative (then removed, re-solved)
  int active_set_passes = 0;  ///< extra CG solves after removing pulling contacts
  int deep_contacts = 0;      ///< inter-body capsule pairs the depenetration pass found too deep (first pass)
  int depenetration_passes = 0;  ///< passes that found deep contacts (and moved poses) this step
  int contacts() const {
    return inter_body_contacts + intra_body_contacts + ground_contacts + environment_contacts;
  }
};

/// A foot held on the ground while the input plants it (stage_foot_holds.cpp). World frame, metres.
struct FootHold {
  bool ankle = false;  ///< the ankle joint is planted and held at ankle_anchor_m
  bool ball = false;   ///< the ball ("foot") joint is planted and held at ball_anchor_m
  Vec3 ankle_anchor_m = Vec3::Zero();
  Vec3 ball_anchor_m = Vec3::Zero();
  Quat rotation_offset = Quat::Identity();  ///< output foot rotation = offset * input foot rotation
  /// How far (m) the anchors were moved this step because the leg was deep in an environment box
  /// (stage_depenetrate.cpp, held feet giving way); reset every step by update_foot_holds.
  double given_way_m = 0.0;
  /// lift_off_knees (issue 27, session 18): a foot held at its ball only whose knee is far off the input's
  /// flexion turns about the ball so that the knee returns at the rate (stage_foot_holds.cpp).
  bool pivot_on_ball = false;
  bool held() const { return ankle || ball; }
};

/// The foot joints, in the order of CorrectorState::foot_start_m (4 per character).
inline constexpr std::array<int, 4> kFootJointOrder = {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot};

/// Capsule pairs (local bone indices of the pair's first and second character) near each other.
using NearCapsulePairs = std::vector<std::pair<std::uint8_t, std::uint8_t>>;

/// Capsule pairs of two characters whose bounding spheres are farther apart than this (m) at the
/// predicted state are not tested by the depenetration pass (stage_depenetrate.cpp), which only
/// removes what the step left: the step's contact response moves a bone relative to a neighbour by a
/// few centimetres. Measured on gomez2024 (corridor 6.66 and stationary 4.44 /m^2, 4 s): of the contacts
/// deeper than 1 cm after a step, 5 of ~300 were outside a 4 cm list (6 cm: 2 of ~270; pairs closer
/// than 3 cm by capsule distance, within the 1 cm body boxes: 196 of 421).
inline constexpr double kNearMargin_m = 0.04;

/// How far apart (m) the broad and narrow phases look: the contact offset, or the depenetration margin
/// when that pass is on.
inline double detection_reach(const CorrectorParams& p) {
  return std::max(p.contact_offset_m, p.depenetration_passes > 0 ? kNearMargin_m : 0.0);
}

/// An inter-body capsule pair the depenetration pass separates (stage_depenetrate.cpp). World frame.
struct DeepContact {
  int bone_a = -1, bone_b = -1;                         ///< global bone indices
  double depth_m = 0.0;                                 ///< penetration depth of the posed capsules (m)
  double share_a = 0.5;                                 ///< fraction of depth_m that bone_a's character takes
  Vec3 normal = Vec3::UnitY();                          ///< unit, from b toward a
  Vec3 point_a = Vec3::Zero(), point_b = Vec3::Zero();  ///< closest points on the two axes (m)
};

/// A surface (environment box face or the ground) that the depenetration pass may not push a capsule
/// through (stage_depenetrate.cpp, surface guards): its depth now (m, < 0 a gap), the unit outward normal
/// and the capsule axis point it is measured at, on bone `bone` (local index). World frame.
struct SurfaceGap {
  int bone = 0;
  double depth_m = 0.0;
  double allowed_m = 0.0;  ///< how deep (m) the pass may take it where it is not that deep already
  Vec3 normal = Vec3::UnitY(), point = Vec3::Zero();
  bool guarded = false;  ///< its row is among the character's rows in this pass
};

/// Variables of one character's pose change in the depenetration pass: root translation (m), then a
/// world-frame rotation vector (rad) per joint.
inline constexpr int kPoseChangeVariables = 3 + 3 * kJointCount;
using PoseChangeVector = Eigen::Matrix<double, kPoseChangeVariables, 1>;

/// Working memory of the depenetration pass, kept between steps: once its buffers have grown, the pass
/// makes no heap allocation of its own (its dense solves use fixed-capacity Eigen matrices).
struct DepenetrationScratch {
  std::vector<BoneTransforms> bones;                  ///< per character, posed bone frames
  std::vector<WorldCapsules> capsules;                ///< per character, posed capsules
  std::vector<std::array<Aabb, kJointCount>> boxes;   ///< per character, the posed capsules' boxes
  std::vector<PoseChangeVector> inverse_weights;      ///< per character, K^-1 (model constants)
  std::vector<std::vector<DeepContact>> per_pair;     ///< per body pair, this pass's deep contacts
  std::vector<std::vector<DeepContact>> environment;  ///< per character, its deep box contacts (bone_b -1)
  std::vector<std::vector<const DeepContact*>> mine;  ///< per character, the deep contacts touching it
  /// per character, its capsules near a box or the ground (the pass's surface guards, stage_depenetrate)
  std::vector<std::vector<SurfaceGap>> gaps;
  std::vector<std::vector<int>> pairs_of;        ///< per character, tested body pairs touching it
  std::vector<char> in_list, moved, ever_moved;  ///< per character flags
  std::vector<int> characters;                   ///< characters with a near capsule pair or box this step
  std::vector<int> posing;                       ///< characters (re-)posed by the current pass
  std::vector<int> tested;                       ///< body pairs (re-)tested by the current pass
  std::vector<int> solved;                       ///< characters with a deep contact in the current pass
  std::vector<int> changed;                      ///< characters the pass moved this step
};

struct CorrectorState {
  bool initialized = false;
  std::int64_t step_index = 0;

  // ---- rigid-body state q (per bone), world frame
  std::vector<Vec3> com_m;         ///< centre of mass (m)
  std::vector<Quat> rotation;      ///< bone frame -> world
  std::vector<Vec3> velocity_mps;  ///< COM velocity (m/s)
  std::vector<Vec3> omega_radps;   ///< angular velocity, world frame (rad/s)

  // ---- targets (per character / per bone)
  std::vector<Pose> target, target_old;  ///< this step's and the previous step's input poses
  std::vector<Pose> output;              ///< the projected poses returned by the step
  /// Target motion per bone (world frame), for the inertial feed-forward (see stage_assemble):
  std::vector<Vec3> target_com_m;         ///< COM of the target pose's bone (m)
  std::vector<Quat> target_rotation;      ///< bone -> world rotation of the target pose
  std::vector<Vec3> target_velocity_mps;  ///< target COM velocity over the last step (m/s)
  std::vector<Vec3> target_omega_radps;   ///< target angular velocity over the last step (rad/s)
  std::vector<Vec3> target_accel_mps2;    ///< target COM acceleration this step (m/s^2)
  std::vector<Vec3> target_alpha_radps2;  ///< target angular acceleration this step (rad/s^2)
  /// World position of every target joint (bone origin) at this step and the previous one (m), for
  /// the foot anchors.
  std::vector<Vec3> target_origin_m, target_origin_old_m;
  /// Per character and foot (2c = left, 2c+1 = right): where planted feet are held.
  std::vector<FootHold> foot_holds;
  bool foot_holds_enabled = true;
  /// Per character, the world positions (m) of its foot joints in the last output (kFootJointOrder):
  /// where this step's foot motion is measured from (the depenetration pass's foot budget).
  std::vector<Vec3> foot_start_m;  ///< Corrector::set_foot_holds (off while an offline run settles)

  // ---- contact-free prediction (stage_predict): the step every body would take if nothing touched it
  std::vector<Vec6> dq_free;        ///< per bone increment (dx m, dtheta rad), solution of T dq = b
  std::vector<Vec3> pred_com_m;     ///< COM after dq_free (m)
  std::vector<Quat> pred_rotation;  ///< rotation after dq_free

  // ---- broad/narrow phase scratch
  std::vector<Capsule> world_capsule;  ///< per bone, world frame, predicted state
  std::vector<Aabb> capsule_box;       ///< per bone: AABB of the world capsule grown by detection_reach
  std::vector<Vec4> capsule_sphere;    ///< per bone: bounding sphere (centre xyz, radius) of the capsule
  std::vector<Aabb> body_box;          ///< per character, capsule AABB
  std::vector<int> sweep_order;        ///< characters sorted by body_box.lo.x
  std::vector<std::pair<int, int>> body_pairs;          ///< (i < j) candidate character pairs
  std::vector<std::vector<Contact>> per_pair_contacts;  ///< narrow-phase output per body pair
  std::vector<NearCapsulePairs> per_pair_near;          ///< per body pair: capsule pairs within kNearMargin_m
  std::vector<std::vector<Contact>> per_body_contacts;  ///< intra/ground/env output per character
  std::vector<std::array<int, 3>> per_body_counts;      ///< (intra, ground, env) per character
  std::vector<Contact> contacts;                        ///< all contacts, fixed order
  /// Contacts touching each character: CSR over characters of (contact index * 2 + side).
  /// Entry 2k means "side a of contact k", 2k+1 "side b"; a self contact appears once (as 2k).
  std::vector<int> incidence_offset, incidence, incidence_cursor;

  // ---- linear system H dq = b (per bone blocks); tree part + contact rank-1 terms
  std::vector<Mat6> diag;               ///< H[b,b] without contact terms
  std::vector<JointCoupling> coupling;  ///< H[b, parent(b)] (child rows, parent columns); unused for roots
  std::vector<Mat6> precond;   ///< per bone: diagonal block to factorise, then S^-1 after factorising
  std::vector<Vec6> rhs;       ///< b = -gradient (tree part + contacts)
  std::vector<Vec6> rhs_tree;  ///< the tree part of b alone (every term but E_collisions)
  std::vector<Vec6> cg_x, cg_r, cg_z, cg_p, cg_q;  ///< CG vectors
  std::vector<Vec6> cg_p_next;                     ///< the next p while the last one is still read
  std::vector<double> partial, partial2,
      partial3;                     ///< per character: partial dot products (fixed-order reduce)
  std::vector<char> factor_ok;      ///< per character: preconditioner blocks were SPD
  std::vector<char> has_contacts;   ///< per character: some contact touches it this step
  std::vector<char> bad_character;  ///< per character: the integrated step is non-finite/too fast

  // ---- the contact-free factorisation of stage_predict, per bone: S^-1 and the block its elimination
  // subtracts from its parent's (H[b,p]^T S^-1 H[b,p]); stage_solve reuses both for every bone whose
  // subtree has no contact block (tree_factor.hpp)
  std::vector<Mat6> tree_inverse, tree_update;
  std::vector<BoneMask> contact_blocks;  ///< per character: bones with a contact block in precond

  // ---- two-phase commit
  std::vector<Vec3> new_com_m;
  std::vector<Quat> new_rotation;

  DepenetrationScratch depenetration;

  // ---- free joints (stage_free_joints.cpp)
  std::vector<BoneMask> touched;  ///< per character: bones in contact this step
  std::vector<std::array<BoneMask, 2>>
      pair_touched;                         ///< per body pair: its characters' touched bones (narrow phase)
  std::vector<std::int64_t> engaged_until;  ///< per bone (joint): last step on which it stays engaged
  std::vector<Quat> output_deviation;       ///< per bone: target local^-1 * output local, last output

  StepStats stats;
};

/// A state sized for `model`, not yet initialised (the first step starts at rest on its targets).
CorrectorState make_corrector_state(const CorrectorModel& model);

}  // namespace crowdlab
