#pragma once
// Derivative-free bound-constrained minimisation with NLopt (Johnson, "The NLopt nonlinear-optimization
// package", Debian libnlopt-dev), as the mixed models here use it: BOBYQA (Powell 2009), lme4's default
// for lmer, or COBYLA for a single parameter (NLopt's BOBYQA needs two or more). Tolerances are tight
// (ftol_rel 1e-15, xtol_rel 1e-10) so that estimates agree with R's tightly converged fits.
#include <nlopt.h>

#include <cmath>
#include <vector>

namespace crowdlab::analysis {

struct NloptOutcome {
  double value = HUGE_VAL;
  nlopt_result status = NLOPT_FAILURE;
  /// Success, or SLSQP/BOBYQA stopping at an optimum it cannot refine further (roundoff).
  bool converged() const { return status > 0 || status == NLOPT_ROUNDOFF_LIMITED; }
};

/// Minimises f from x (updated in place) with lower bounds `lower` (empty: none); `ftol_rel` looser than
/// the default for a caller that polishes the optimum itself (clmm_fit's Newton steps).
inline NloptOutcome minimise_derivative_free(std::vector<double>& x, const std::vector<double>& lower,
                                             nlopt_func f, void* data, int max_evaluations,
                                             double ftol_rel = 1e-15) {
  const auto n = static_cast<unsigned>(x.size());
  nlopt_opt opt = nlopt_create(n >= 2 ? NLOPT_LN_BOBYQA : NLOPT_LN_COBYLA, n);
  if (!lower.empty()) nlopt_set_lower_bounds(opt, lower.data());
  nlopt_set_min_objective(opt, f, data);
  nlopt_set_ftol_rel(opt, ftol_rel);
  nlopt_set_xtol_rel(opt, 1e-10);
  nlopt_set_maxeval(opt, max_evaluations);
  NloptOutcome out;
  out.status = nlopt_optimize(opt, x.data(), &out.value);
  nlopt_destroy(opt);
  return out;
}

}  // namespace crowdlab::analysis
