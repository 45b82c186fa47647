// The contact-free prediction (see corrector_step.hpp): every character's tree part T of the Newton
// matrix is factorised exactly (tree_factor.hpp) and solved, T dq_free = b. dq_free is the step each
// body would take if nothing touched it; collisions are then detected at q_old + dq_free, and CG
// starts from dq_free. Characters that meet no contact keep this factorisation as their
// preconditioner block, and dq_free is already their exact solution.
#include <tbb/parallel_for.h>

#include "framework/correction/corrector_step.hpp"
#include "framework/correction/tree_factor.hpp"

namespace crowdlab {

void stage_predict(const CorrectorModel& model, CorrectorState& s) {
  const double h = model.h;
  tbb::parallel_for(0, model.characters(), [&](int c) {
    const size_t base = static_cast<size_t>(c) * kJointCount;
    if (model.params.exact_prediction) {
      s.factor_ok[static_cast<size_t>(c)] = factor_tree_character(s, c) ? 1 : 0;
      apply_tree_inverse(s, c, s.rhs_tree, s.dq_free);
    } else {
      for (size_t g = base; g < base + kJointCount; ++g) {
        s.dq_free[g].head<3>() = h * s.velocity_mps[g] + h * h * s.target_accel_mps2[g];
        s.dq_free[g].tail<3>() = h * s.omega_radps[g] + h * h * s.target_alpha_radps2[g];
      }
    }
    for (size_t g = base; g < base + kJointCount; ++g) {
      s.pred_com_m[g] = s.com_m[g] + s.dq_free[g].head<3>();
      s.pred_rotation[g] = (rotation_from_vector(s.dq_free[g].tail<3>()) * s.rotation[g]).normalized();
    }
  });
}

}  // namespace crowdlab
