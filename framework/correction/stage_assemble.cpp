// Assemble the Newton system of seed 000 Eq. 3 at the start-of-step state q_old (one Newton
// iteration; increments dq = (dx, dtheta) per bone, world frame). stage_assemble builds the tree part
// (every term but the collisions); stage_assemble_contacts adds E_collisions, linearised at the
// contact-free predicted state where the contacts were found (see corrector_step.hpp):
//
//   E_inertia   = 1/(2h^2) (dq - h v_old - h^2 a_hat)^T M (dq - h v_old - h^2 a_hat),
//                 M = diag(m I3, I_world) (Gast et al. 2015). a_hat is the acceleration of the target
//                 bone (from the last three target frames): an inertial feed-forward, as in
//                 computed-torque control (Khatib 1987), ours; without it a PD-tracked body lags its
//                 input by ~(omega_input / omega_n)^2 even with no contact. The gyroscopic term is
//                 dropped, as is usual for one linearised step.
//   E_gravity   = m g y_com   (cancelled by the controller's feed-forward if gravity_compensation)
//   E_joints    = 1/2 k_J |o_child - (o_parent + R_parent offset)|^2   (soft ball joint)
//   E_control   = Eq. 4 on relative rotations R = R_parent^T R_child (absolute for the root),
//                 plus the same spring/damper on the root position (seed 000 §3.3)
//   E_collision = 1/2 k delta^2 per contact (seed 000 §3.4)
//
// Hessians are Gauss-Newton (J^T K J, PSD): for Eq. 4 the Jacobian of the 9-vector R(w) w.r.t. the
// world rotation increment w = dtheta_child - dtheta_parent has columns vec(R_p^T [e_k]x R_c), whose
// Gram matrix is exactly 2 I3, so the GN Hessian of Eq. 4 is 2 (k + d/h^2) I3 on w.
#include <tbb/parallel_for.h>

#include "framework/core/forward_kinematics.hpp"
#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
namespace {

/// (<[e_x]x, N>, <[e_y]x, N>, <[e_z]x, N>) for the Frobenius inner product.
Vec3 skew_projection(const Mat3& n) {
  return {n(2, 1) - n(1, 2), n(0, 2) - n(2, 0), n(1, 0) - n(0, 1)};
}

/// Jacobian (3 x 6) of a point rigidly attached to a bone, p = com + arm: dp = dx - [arm]x dtheta.
Eigen::Matrix<double, 3, 6> point_jacobian(const Vec3& arm) {
  Eigen::Matrix<double, 3, 6> a;
  a.leftCols<3>() = Mat3::Identity();
  a.rightCols<3>() = -skew(arm);
  return a;
}

/// d += k a^T a for a = point_jacobian(arm) = [I, S], S = -[arm]x, with the values Eigen's product
/// `k * a.transpose() * a` gives (bit-identical) at a fifth of its cost: every entry of that product has
/// at most two non-zero terms (k a_mi) a_mj (the others are exact zeros, and d's entries are never -0),
/// so the zeros need not be multiplied nor the 6 x 6 temporary formed.
void add_point_hessian(Mat6& d, double k, const Vec3& arm) {
  const Mat3 s = -skew(arm);
  for (int i = 0; i < 3; ++i) {
    d(i, i) += k;
    for (int j = 0; j < 3; ++j) {
      d(i, 3 + j) += k * s(i, j);
      d(3 + i, j) += k * s(j, i);
      double v = 0.0;
      for (int m = 0; m < 3; ++m)
        if (m != i && m != j) v += (k * s(m, i)) * s(m, j);
      d(3 + i, 3 + j) += v;
    }
  }
}

Vec6 contact_row(const Vec3& normal, const Vec3& arm, double sign) {
  Vec6 w;
  w.head<3>() = sign * normal;
  w.tail<3>() = sign * arm.cross(normal);
  return w;
}

void assemble_character(const CorrectorModel& model, CorrectorState& s, int c) {
  const CorrectorBody& body = model.bodies[static_cast<size_t>(c)];
  const CorrectorParams& p = model.params;
  const double h = model.h, inv_h2 = 1.0 / (h * h);
  const int base = c * kJointCount;
  const Pose& target = s.target[static_cast<size_t>(c)];
  const Pose& target_old = s.target_old[static_cast<size_t>(c)];
  std::array<Mat3, kJointCount> rot;
  std::array<Vec3, kJointCount> origin;

  // E_inertia and E_gravity (block diagonal).
  for (size_t j = 0; j < kJointCount; ++j) {
    const size_t g = static_cast<size_t>(base) + j;
    rot[j] = s.rotation[g].toRotationMatrix();
    origin[j] = s.com_m[g] - rot[j] * body.com_local_m[j];
    const double m = body.mass_kg[j];
    const Mat3 inertia = rot[j] * body.inertia_local[j] * rot[j].transpose();
    Mat6& d = s.diag[g];
    d.setZero();
    d.topLeftCorner<3, 3>() = (m * inv_h2) * Mat3::Identity();
    d.bottomRightCorner<3, 3>() = inv_h2 * inertia;
    Vec6& b = s.rhs[g];
    // Inertial feed-forward: the predicted motion includes the target's own acceleration, so with no
    // contact the deviation from the input stays zero (computed-torque feed-forward; see header).
    b.head<3>() = m * (s.velocity_mps[g] / h + s.target_accel_mps2[g]);
    b.tail<3>() = inertia * (s.omega_radps[g] / h + s.target_alpha_radps2[g]);
    if (!p.gravity_compensation) b[1] -= m * p.gravity_mps2;  // -dE_gravity/dy
    s.coupling[g] = JointCoupling{};
  }

  // E_joints and E_control for every non-root joint (child j, parent pj).
  for (size_t j = 1; j < kJointCount; ++j) {
    const size_t pj = static_cast<size_t>(kJointParent[j]);
    const size_t gc = static_cast<size_t>(base) + j, gp = static_cast<size_t>(base) + pj;
    const Vec3 attach = origin[pj] + rot[pj] * body.shape.joint_offsets_m[j];
    const Vec3 r0 = origin[j] - attach;
    const auto a_c = point_jacobian(origin[j] - s.com_m[gc]);
    const auto a_p = point_jacobian(attach - s.com_m[gp]);
    const double kj = body.joint_stiffness[j];
    add_point_hessian(s.diag[gc], kj, origin[j] - s.com_m[gc]);  // kj a_c^T a_c
    add_point_hessian(s.diag[gp], kj, attach - s.com_m[gp]);     // kj a_p^T a_p
    JointCoupling& coupling = s.coupling[gc];
    coupling.arm_child = origin[j] - s.com_m[gc];
    coupling.arm_parent = attach - s.com_m[gp];
    coupling.joint_k = kj;
    s.rhs[gc] -= kj * a_c.transpose() * r0;
    s.rhs[gp] += kj * a_p.transpose() * r0;

    const Mat3 rel = rot[pj].transpose() * rot[j];
    const Mat3 rel_hat = target.local_rotations[j].toRotationMatrix();
    const Mat3 rel_hat_old = target_old.local_rotations[j].toRotationMatrix();
    const double ks = body.rot_stiffness[j], kd = body.rot_damping[j] * inv_h2;
    const Mat3 resid = ks * (rel - rel_hat) - kd * (rel_hat - rel_hat_old);
    const Vec3 grad_w = skew_projection(rot[pj] * resid * rot[j].transpose());
    const double c2 = 2.0 * (ks + kd);
    s.diag[gc].bottomRightCorner<3, 3>() += c2 * Mat3::Identity();
    s.diag[gp].bottomRightCorner<3, 3>() += c2 * Mat3::Identity();
    coupling.rot_k = c2;
    s.rhs[gc].tail<3>() -= grad_w;
    s.rhs[gp].tail<3>() += grad_w;
  }

  // Root: absolute rotation (Eq. 4 on R_root) and absolute translation of the pelvis joint.
  {
    const size_t g = static_cast<size_t>(base);
    const Mat3 r_hat = target.local_rotations[0].toRotationMatrix();
    const Mat3 r_hat_old = target_old.local_rotations[0].toRotationMatrix();
    const double ks = body.rot_stiffness[0], kd = body.rot_damping[0] * inv_h2;
    const Mat3 resid = ks * (rot[0] - r_hat) - kd * (r_hat - r_hat_old);
    const Vec3 grad = skew_projection(resid * rot[0].transpose());
    s.diag[g].bottomRightCorner<3, 3>() += 2.0 * (ks + kd) * Mat3::Identity();
    s.rhs[g].tail<3>() -= grad;

    const double kt = body.root_translation_stiffness, dt = body.root_translation_damping * inv_h2;
    const Vec3 resid_t = kt * (origin[0] - target.root_position_m) -
                         dt * (target.root_position_m - target_old.root_position_m);
    const auto a = point_jacobian(origin[0] - s.com_m[g]);
    add_point_hessian(s.diag[g], kt + dt, origin[0] - s.com_m[g]);  // (kt + dt) a^T a
    s.rhs[g] -= a.transpose() * resid_t;
  }

  // Feet: a planted foot's ankle and ball joints are held on their anchors by a world spring (seed 000
  // §3.3, see params and stage_foot_holds.cpp): horizontally where the foot landed, vertically at the
  // input's height (issue 18: held horizontally only, whole bodies floated 2-5 cm up on their planted
  // feet). The anchor is still, so the damper acts on the joint's own velocity. A swinging foot is pulled
  // toward its target by a spring 40x weaker (swing_foot_stiffness), with the Eq. 4 damper on its
  // deviation velocity: weak enough to step around neighbours' legs, strong enough that feet keep
  // landing where the input puts them.
  if (body.foot_anchor_stiffness > 0.0 || body.foot_anchor_damping > 0.0) {
    const double kt = body.foot_anchor_stiffness, dt = body.foot_anchor_damping * inv_h2;
    for (int side = 0; side < 2; ++side) {
      const size_t ankle = side == 0 ? size_t{kLeftAnkle} : size_t{kRightAnkle};
      const size_t ball = side == 0 ? size_t{kLeftFoot} : size_t{kRightFoot};
      if (!s.foot_holds_enabled || !s.foot_holds[static_cast<size_t>(2 * c + side)].held()) {
        // Not held: toward the target, weakly while swinging, at full strength while holds are off
        // (an offline run settling on its first frame).
        const double k = s.foot_holds_enabled ? body.swing_foot_stiffness : kt;
        for (const size_t j : {ankle, ball}) {
          const size_t g = static_cast<size_t>(base) + j;
          const Vec3& goal = s.target_origin_m[g];
          const auto a = point_jacobian(origin[j] - s.com_m[g]);
          s.diag[g] += (k + dt) * a.transpose() * a;
          s.rhs[g] -= a.transpose() * (k * (origin[j] - goal) - dt * (goal - s.target_origin_old_m[g]));
        }
        continue;
      }
      const FootGoal goal = foot_goal(model, s, c, side);
      for (const auto& [j, anchor] : {std::pair{ankle, goal.ankle_m}, std::pair{ball, goal.ball_m}}) {
        const size_t g = static_cast<size_t>(base) + j;
        const auto a = point_jacobian(origin[j] - s.com_m[g]);
        s.diag[g] += (kt + dt) * a.transpose() * a;
        s.rhs[g] -= a.transpose() * (kt * (origin[j] - anchor));
      }
    }
  }

  for (size_t j = 0; j < kJointCount; ++j) {
    s.precond[static_cast<size_t>(base) + j] = s.diag[static_cast<size_t>(base) + j];
    s.rhs_tree[static_cast<size_t>(base) + j] = s.rhs[static_cast<size_t>(base) + j];
  }
}

/// Adds character c's incident contacts: their diagonal blocks k w w^T to the preconditioner blocks
/// (precond, reset to the tree diagonal first) and their gradient k depth0 w to the right-hand side.
}  // namespace

void assemble_character_contacts(CorrectorState& s, int c) {
  const size_t base = static_cast<size_t>(c) * kJointCount;
  for (size_t j = base; j < base + kJointCount; ++j) {
    s.precond[j] = s.diag[j];
    s.rhs[j] = s.rhs_tree[j];
  }
  BoneMask& blocks = s.contact_blocks[static_cast<size_t>(c)];
  blocks = 0;
  const int begin = s.incidence_offset[static_cast<size_t>(c)],
            end = s.incidence_offset[static_cast<size_t>(c) + 1];
  for (int e = begin; e < end; ++e) {
    const int entry = s.incidence[static_cast<size_t>(e)];
    const Contact& k = s.contacts[static_cast<size_t>(entry / 2)];
    if (k.stiffness == 0.0) continue;  // removed by the active set (stage_solve)
    const bool side_b = (entry & 1) != 0;
    const bool self = k.bone_b >= 0 && k.bone_b / kJointCount == k.bone_a / kJointCount;
    auto add_side = [&](int bone, const Vec6& w) {
      blocks |= BoneMask{1} << (bone % kJointCount);
      s.precond[static_cast<size_t>(bone)] += (k.stiffness * w) * w.transpose();
      s.rhs[static_cast<size_t>(bone)] -= (k.stiffness * k.depth0) * w;
    };
    if (side_b) {
      add_side(k.bone_b, k.w_b);
    } else {
      add_side(k.bone_a, k.w_a);
      if (self) add_side(k.bone_b, k.w_b);
    }
  }
}

void stage_assemble(const CorrectorModel& model, CorrectorState& state) {
  tbb::parallel_for(0, model.characters(), [&](int c) { assemble_character(model, state, c); });
}

void stage_assemble_contacts(const CorrectorModel& model, CorrectorState& state) {
  // Contact Jacobian rows at the predicted state: delta decreases when a moves along +n or b along -n.
  // depth0 moves the linearisation point from the prediction back to dq = 0 (see Contact).
  tbb::parallel_for(size_t{0}, state.contacts.size(), [&](size_t k) {
    Contact& c = state.contacts[k];
    const auto a = static_cast<size_t>(c.bone_a);
    c.w_a = contact_row(c.normal, c.point_a - state.pred_com_m[a], -1.0);
    c.depth0 = c.depth_m - c.w_a.dot(state.dq_free[a]);
    if (c.bone_b >= 0) {
      const auto b = static_cast<size_t>(c.bone_b);
      c.w_b = contact_row(c.normal, c.point_b - state.pred_com_m[b], +1.0);
      c.depth0 -= c.w_b.dot(state.dq_free[b]);
    }
  });
  tbb::parallel_for(0, model.characters(), [&](int c) {
    const auto cc = static_cast<size_t>(c);
    state.has_contacts[cc] = state.incidence_offset[cc + 1] > state.incidence_offset[cc] ? 1 : 0;
    if (state.has_contacts[cc]) assemble_character_contacts(state, c);
  });
}

}  // namespace crowdlab
