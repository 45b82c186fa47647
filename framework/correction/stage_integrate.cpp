// Integrate and project (seed 000 §3.2: "after each time-step solve, we project the rigid-body state
// q to each body's parametric pose theta"). Two phases: first every character's new state is computed
// into new_com_m / new_rotation from the old state; then, if the whole step is sound, it is committed.
//
// Projection: joint rotations are read from the bones (R_parent^T R_child) and the root position from
// the pelvis bone's origin; the bones are then rebuilt by forward kinematics from that pose, so the
// soft joints never accumulate a gap. Velocities are the backward-Euler ones of the projected motion,
// v = (x_new - x_old) / h and omega = log(R_new R_old^T) / h.
//
// Trust region (params.max_rotation_step_rad): before integrating, each bone's rotation increment is
// kept within theta_max of its contact-free increment dq_free (the part of the step that contacts
// added is scaled down, its direction kept). The Newton step linearises every bone point as
// dx + dtheta x r, valid only for small dtheta; light bones (hands, toes) otherwise spin by radians in
// one step. Clamping one bone's rotation leaves the joints slightly inconsistent, which the projection
// below removes like any other joint gap.
//
// A step is rejected (state kept, velocities zeroed, a warning logged) when the solve produced
// non-finite numbers, a preconditioner block was not positive definite, CG stalled above 10 % relative
// residual, or any bone would exceed max_bone_speed_mps.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"

namespace crowdlab {
Quat rotation_from_vector(const Vec3& v) {
  const double angle = v.norm();
  if (angle < 1e-12) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, v / angle));
}

namespace {
void limit_rotation_steps(CorrectorState& s, size_t base, double theta_max) {
  if (!(theta_max > 0.0)) return;
  for (size_t j = base; j < base + kJointCount; ++j) {
    const Vec3 contact_part = s.cg_x[j].tail<3>() - s.dq_free[j].tail<3>();
    const double angle = contact_part.norm();
    if (angle > theta_max) s.cg_x[j].tail<3>() = s.dq_free[j].tail<3>() + contact_part * (theta_max / angle);
  }
}
}  // namespace

void stage_integrate(const CorrectorModel& model, CorrectorState& s) {
  const int n = model.characters();
  const double h = model.h;
  const double max_speed = model.params.max_bone_speed_mps;
  const bool solve_ok = std::isfinite(s.stats.cg_relative_residual) && s.stats.cg_relative_residual < 0.1;
  std::vector<char>& fast = s.bad_character;
  tbb::parallel_for(0, n, [&](int c) {
    const size_t base = static_cast<size_t>(c) * kJointCount;
    limit_rotation_steps(s, base, model.params.max_rotation_step_rad);
    for (size_t j = base; j < base + kJointCount; ++j) {
      s.new_com_m[j] = s.com_m[j] + s.cg_x[j].head<3>();
      s.new_rotation[j] = (rotation_from_vector(s.cg_x[j].tail<3>()) * s.rotation[j]).normalized();
    }
    Pose pose = pose_from_bones(model, c, s.new_com_m, s.new_rotation);
    release_free_joints(model, s, c, pose);
    hold_feet(model, s, c, pose);
    set_bones_from_pose(model, c, pose, s.new_com_m, s.new_rotation);
    bool bad = false;
    for (size_t j = base; j < base + kJointCount; ++j) {
      const Vec3 dx = s.new_com_m[j] - s.com_m[j];
      if (!dx.allFinite() || !s.new_rotation[j].coeffs().allFinite() || dx.norm() > max_speed * h) bad = true;
    }
    fast[static_cast<size_t>(c)] = bad ? 1 : 0;
    s.output[static_cast<size_t>(c)] = pose;
  });
  const bool any_bad = std::any_of(fast.begin(), fast.end(), [](char v) { return v != 0; });
  if (!solve_ok || any_bad) {
    s.stats.rejected = true;
    spdlog::warn(
        "corrector: step {} rejected ({}); keeping the last stable state", s.step_index,
        any_bad ? "a bone moved too fast or became non-finite" : "the linear solve did not converge");
    std::fill(s.velocity_mps.begin(), s.velocity_mps.end(), Vec3::Zero());
    std::fill(s.omega_radps.begin(), s.omega_radps.end(), Vec3::Zero());
    tbb::parallel_for(0, n, [&](int c) {
      s.output[static_cast<size_t>(c)] = pose_from_bones(model, c, s.com_m, s.rotation);
    });
    return;
  }
  if (!s.stats.converged)
    spdlog::debug("corrector: step {}: CG stopped at relative residual {:.2e} after {} iterations",
                  s.step_index, s.stats.cg_relative_residual, s.stats.cg_iterations);
  tbb::parallel_for(size_t{0}, s.com_m.size(), [&](size_t j) {
    s.velocity_mps[j] = (s.new_com_m[j] - s.com_m[j]) / h;
    s.omega_radps[j] = rotation_vector(s.new_rotation[j] * s.rotation[j].conjugate()) / h;
    s.com_m[j] = s.new_com_m[j];
    s.rotation[j] = s.new_rotation[j];
  });
}

}  // namespace crowdlab
