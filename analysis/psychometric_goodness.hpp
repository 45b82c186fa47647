#pragma once
// Goodness of fit of a psychometric function, the overdispersion check of psignifit 4 (Schuett,
// Harmeling, Macke & Wichmann 2016, Vision Research 122, section 2.4) in its classical form (Wichmann &
// Hill 2001a, section 3): the deviance of the binomial model against the saturated model over the
// distinct stimulus levels,
//   D = 2 sum_x [ k ln(k / (n p)) + (n - k) ln((n - k) / (n (1 - p))) ],   df = levels - parameters,
// with p the fitted probability at x, k the "yes" count of n trials at x (0 ln 0 = 0). Under the
// binomial model D is approximately chi-square(df); a large D (p < 0.05), or D / df well above 1, means
// the answers vary more than a binomial allows (non-stationary observers, lapses in bursts) and the
// thresholds' binomial confidence intervals are too narrow. Wichmann & Hill note that the chi-square
// approximation is poor with few trials per level: the p is a screening flag, not a test to report.
#include <vector>

#include "analysis/psychometric_fit.hpp"

namespace crowdlab::analysis {

struct PsychometricGoodness {
  double deviance = 0;
  int df = 0;                  ///< distinct x levels - fitted parameters (0 or less: no test)
  double p = 0;                ///< chi-square(df) upper tail of the deviance; NaN when df <= 0
  double dispersion = 0;       ///< deviance / df; NaN when df <= 0
  bool overdispersed = false;  ///< p < 0.05
};

/// `parameters` = 2 for a fixed lapse, 3 when the lapse rate was fitted.
PsychometricGoodness psychometric_goodness(const std::vector<double>& x, const std::vector<double>& y,
                                           const PsychometricFit& fit, int parameters);

}  // namespace crowdlab::analysis
