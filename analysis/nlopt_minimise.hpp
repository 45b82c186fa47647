#pragma once
// Minimisation with NLopt (Johnson, "The NLopt nonlinear-optimization package", Debian libnlopt-dev), as
// the mixed models here use it: derivative-free BOBYQA (Powell 2009), lme4's default for lmer, or COBYLA
// for a single parameter (NLopt's BOBYQA needs two or more); L-BFGS where the gradient is known (CLMM).
// Tolerances are tight (ftol_rel 1e-15, xtol_rel 1e-10) so that estimates agree with R's tightly converged
// fits.
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

/// Runs `algorithm` on f from x (updated in place): lower bounds `lower` (empty: none), the tolerances
/// above (`ftol_rel` looser for a caller that polishes the optimum itself: clmm_fit's Newton steps).
inline NloptOutcome minimise_with(nlopt_algorithm algorithm, std::vector<double>& x,
                                  const std::vector<double>& lower, nlopt_func f, void* data,
                                  int max_evaluations, double ftol_rel) {
  nlopt_opt opt = nlopt_create(algorithm, static_cast<unsigned>(x.size()));
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

/// Minimises f from x (updated in place) with lower bounds `lower` (empty: none) without derivatives.
inline NloptOutcome minimise_derivative_free(std::vector<double>& x, const std::vector<double>& lower,
                                             nlopt_func f, void* data, int max_evaluations,
                                             double ftol_rel = 1e-15) {
  return minimise_with(x.size() >= 2 ? NLOPT_LN_BOBYQA : NLOPT_LN_COBYLA, x, lower, f, data, max_evaluations,
                       ftol_rel);
}

/// Minimises f, which fills its gradient when asked, from x (updated in place) by NLopt's limited-memory
/// BFGS (Nocedal 1980; Liu & Nocedal 1989), without bounds.
inline NloptOutcome minimise_with_gradient(std::vector<double>& x, nlopt_func f, void* data,
                                           int max_evaluations, double ftol_rel = 1e-15) {
  return minimise_with(NLOPT_LD_LBFGS, x, {}, f, data, max_evaluations, ftol_rel);
}

}  // namespace crowdlab::analysis
