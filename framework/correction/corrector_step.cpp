#include "framework/correction/corrector_step.hpp"

#include <string>

#include <tbb/parallel_for.h>

#include <numbers>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

Vec3 rotation_vector(const Quat& q) {
  const Eigen::AngleAxisd aa(q.normalized());
  double angle = aa.angle();
  if (angle > std::numbers::pi) angle -= 2.0 * std::numbers::pi;
  return angle * aa.axis();
}

CorrectorState make_corrector_state(const CorrectorModel& model) {
  CorrectorState s;
  const auto n = static_cast<size_t>(model.characters());
  const auto bones = static_cast<size_t>(model.bones());
  s.com_m.assign(bones, Vec3::Zero());
  s.rotation.assign(bones, Quat::Identity());
  s.velocity_mps.assign(bones, Vec3::Zero());
  s.omega_radps.assign(bones, Vec3::Zero());
  s.target.assign(n, Pose{});
  s.target_old.assign(n, Pose{});
  s.output.assign(n, Pose{});
  s.target_com_m.assign(bones, Vec3::Zero());
  s.target_rotation.assign(bones, Quat::Identity());
  for (auto* v :
       {&s.target_velocity_mps, &s.target_omega_radps, &s.target_accel_mps2, &s.target_alpha_radps2})
    v->assign(bones, Vec3::Zero());
  s.world_capsule.assign(bones, Capsule{});
  s.body_box.assign(n, Aabb{});
  s.capsule_box.assign(bones, Aabb{});
  s.capsule_sphere.assign(bones, Vec4::Zero());
  s.sweep_order.assign(n, 0);
  s.body_pairs.reserve(8 * n);
  s.per_body_contacts.assign(n, {});
  s.per_body_counts.assign(n, {0, 0, 0});
  s.contacts.reserve(32 * n);
  s.incidence_offset.assign(n + 1, 0);
  s.incidence_cursor.assign(n, 0);
  s.diag.assign(bones, Mat6::Zero());
  s.tree_inverse.assign(bones, Mat6::Zero());
  s.tree_update.assign(bones, Mat6::Zero());
  s.contact_blocks.assign(n, 0);
  s.target_origin_m.assign(bones, Vec3::Zero());
  s.target_origin_old_m.assign(bones, Vec3::Zero());
  s.foot_holds.assign(2 * n, FootHold{});
  s.foot_start_m.assign(4 * n, Vec3::Zero());
  s.dq_free.assign(bones, Vec6::Zero());
  s.pred_com_m.assign(bones, Vec3::Zero());
  s.pred_rotation.assign(bones, Quat::Identity());
  s.coupling.assign(bones, JointCoupling{});
  s.precond.assign(bones, Mat6::Zero());
  for (auto* v : {&s.rhs, &s.rhs_tree, &s.cg_x, &s.cg_r, &s.cg_z, &s.cg_p, &s.cg_q, &s.cg_p_next})
    v->assign(bones, Vec6::Zero());
  s.partial.assign(n, 0.0);
  s.partial2.assign(n, 0.0);
  s.partial3.assign(n, 0.0);
  s.factor_ok.assign(n, 1);
  s.has_contacts.assign(n, 0);
  s.bad_character.assign(n, 0);
  s.new_com_m.assign(bones, Vec3::Zero());
  s.new_rotation.assign(bones, Quat::Identity());
  s.touched.assign(n, 0);
  s.engaged_until.assign(bones, -1);
  s.output_deviation.assign(bones, Quat::Identity());
  return s;
}

void set_bones_from_pose(const CorrectorModel& model, int c, const Pose& pose, std::vector<Vec3>& com,
                         std::vector<Quat>& rotation) {
  const CorrectorBody& body = model.bodies[static_cast<size_t>(c)];
  const BoneTransforms bones = forward_kinematics(body.shape, pose);
  for (size_t j = 0; j < kJointCount; ++j) {
    const size_t g = static_cast<size_t>(c) * kJointCount + j;
    rotation[g] = bones[j].rotation;
    com[g] = bones[j].apply(body.com_local_m[j]);
  }
}

Pose pose_from_bones(const CorrectorModel& model, int c, const std::vector<Vec3>& com,
                     const std::vector<Quat>& rotation) {
  const CorrectorBody& body = model.bodies[static_cast<size_t>(c)];
  BoneTransforms bones;
  for (size_t j = 0; j < kJointCount; ++j) {
    const size_t g = static_cast<size_t>(c) * kJointCount + j;
    bones[j].rotation = rotation[g];
    bones[j].translation = com[g] - rotation[g] * body.com_local_m[j];
  }
  return pose_from_bone_transforms(bones);
}

void record_foot_start(const CorrectorModel& model, CorrectorState& state, int c) {
  for (size_t k = 0; k < kFootJointOrder.size(); ++k)
    state.foot_start_m[4 * static_cast<size_t>(c) + k] =
        bone_origin(model, state, c * kJointCount + kFootJointOrder[k]);
}

void stage_targets(const CorrectorModel& model, CorrectorState& state, const std::vector<Pose>& targets) {
  if (targets.size() != static_cast<size_t>(model.characters()))
    throw InputError("corrector: got " + std::to_string(targets.size()) + " target poses for " +
                     std::to_string(model.characters()) + " characters");
  for (size_t c = 0; c < targets.size(); ++c)
    validate_pose(targets[c],
                  "corrector: step " + std::to_string(state.step_index) + " character " + std::to_string(c));
  if (!state.initialized) {
    // Start at rest exactly on the first targets (the input animation's first frame).
    for (int c = 0; c < model.characters(); ++c) {
      Pose p = targets[static_cast<size_t>(c)];
      for (Quat& q : p.local_rotations) q.normalize();
      set_bones_from_pose(model, c, p, state.com_m, state.rotation);
      state.target_old[static_cast<size_t>(c)] = p;
      state.target[static_cast<size_t>(c)] = p;
    }
    state.target_com_m = state.com_m;
    state.target_rotation = state.rotation;
    for (size_t g = 0; g < state.com_m.size(); ++g)
      state.target_origin_m[g] = bone_origin(model, state, static_cast<int>(g));
    state.target_origin_old_m = state.target_origin_m;
    for (int c = 0; c < model.characters(); ++c) record_foot_start(model, state, c);
    for (auto* v : {&state.velocity_mps, &state.omega_radps, &state.target_velocity_mps,
                    &state.target_omega_radps, &state.target_accel_mps2, &state.target_alpha_radps2})
      std::fill(v->begin(), v->end(), Vec3::Zero());
    state.initialized = true;
    return;
  }
  const double h = model.h;
  tbb::parallel_for(0, model.characters(), [&](int c) {
    const size_t cc = static_cast<size_t>(c);
    state.target_old[cc] = state.target[cc];
    state.target[cc] = targets[cc];
    for (Quat& q : state.target[cc].local_rotations) q.normalize();
    // Target bone motion: displacement over this step, acceleration relative to the last step.
    const CorrectorBody& body = model.bodies[cc];
    const std::array<Quat, 2> old_foot_rotation = {state.target_rotation[cc * kJointCount + kLeftAnkle],
                                                   state.target_rotation[cc * kJointCount + kRightAnkle]};
    const BoneTransforms bones = forward_kinematics(body.shape, state.target[cc]);
    for (size_t j = 0; j < kJointCount; ++j) {
      const size_t g = cc * kJointCount + j;
      const Vec3 com = bones[j].apply(body.com_local_m[j]);
      const Vec3 dx = com - state.target_com_m[g];
      const Vec3 dtheta = rotation_vector(bones[j].rotation * state.target_rotation[g].conjugate());
      state.target_accel_mps2[g] = (dx - h * state.target_velocity_mps[g]) / (h * h);
      state.target_alpha_radps2[g] = (dtheta - h * state.target_omega_radps[g]) / (h * h);
      state.target_velocity_mps[g] = dx / h;
      state.target_omega_radps[g] = dtheta / h;
      state.target_com_m[g] = com;
      state.target_rotation[g] = bones[j].rotation;
      state.target_origin_old_m[g] = state.target_origin_m[g];
      state.target_origin_m[g] = bones[j].translation;
    }
    update_foot_holds(model, state, c, old_foot_rotation);
    record_foot_start(model, state, c);
  });
}

const std::vector<Pose>& corrector_step(const CorrectorModel& model, CorrectorState& state,
                                        const std::vector<Pose>& targets) {
  const bool first = !state.initialized;
  stage_targets(model, state, targets);
  state.stats = StepStats{};
  if (first) {  // the state starts at rest on the first targets, which are returned unchanged
    for (size_t c = 0; c < targets.size(); ++c) state.output[c] = state.target[c];
    ++state.step_index;
    return state.output;
  }
  stage_assemble(model, state);
  stage_predict(model, state);
  stage_broad_phase(model, state);
  stage_narrow_phase(model, state);
  stage_contact_scope(model, state);
  stage_assemble_contacts(model, state);
  stage_solve(model, state);
  stage_integrate(model, state);
  stage_depenetrate(model, state);
  stage_record_deviation(model, state);
  stage_settle_feet(model, state);
  ++state.step_index;
  return state.output;
}

}  // namespace crowdlab
