#pragma once
// Psychometric functions for binary answers (seed 001 section 3.2): per participant and condition,
//   P(yes | x) = guess + (1 - guess - lapse) F(intercept + slope x),   F(t) = 1 / (1 + exp(-t)),
// fitted by maximum likelihood. x is the interpersonal distance (P(collision) falls: slope < 0) or
// the cube root of the interpenetration volume (P rises: slope > 0); the caller transforms x.
// - Default guess = lapse = 0: plain logistic regression by Newton-Raphson / IRLS (the same estimate
//   as R's glm(binomial)), with step halving on the log-likelihood.
// - Fixed guess/lapse rates > 0: Fisher scoring on the full likelihood. Thresholds are then points of
//   the UNDERLYING F: threshold(0.5) is where F = 0.5, i.e. where P = guess + (1 - guess - lapse)/2
//   (the midpoint between the floor and the ceiling), not where P = 0.5.
// - Complete or quasi-complete separation (every "yes" at x on one side of every "no", or one answer
//   only) makes the ML slope infinite. It is detected before fitting, a warning is set, and the
//   estimate is Firth's (1993) penalised likelihood (Jeffreys prior), which is always finite
//   (Heinze & Schemper 2002). With guess/lapse rates the Firth fit is of the plain logistic model.
// - Fitted symmetric lapse (options.fit_symmetric_lapse): see psychometric_lapse.hpp. Separated data
//   keep the Firth fit of the plain model (lambda = 0: a lapse cannot raise a likelihood that is 1).
// threshold(p) = (logit(p) - intercept) / slope: D_crit and V_crit at p = 0.5; seed 001 also uses
// the 5 % point (dtca_th).
#include <cstdint>
#include <string>
#include <vector>

namespace crowdlab::analysis {

struct PsychometricOptions {
  double guess = 0.0;  ///< lower asymptote, fixed, in [0, 1)
  double lapse = 0.0;  ///< 1 - upper asymptote, fixed, guess + lapse < 1
  /// Fit guess = lapse = lambda by ML (analysis/psychometric_lapse.hpp); guess and lapse must be 0.
  bool fit_symmetric_lapse = false;
  int max_iterations = 200;
};

struct PsychometricFit {
  double intercept = 0, slope = 0;
  double guess = 0, lapse = 0;
  bool converged = false;
  bool separated = false;            ///< complete/quasi-complete separation: Firth estimate
  bool lapse_fitted = false;         ///< guess = lapse = lambda estimated (symmetric-lapse model)
  bool lapse_at_boundary = false;    ///< the fitted lambda is on its bound 0
  bool step_not_identified = false;  ///< fitted lapse: a step fits as well, slope/threshold not identified
  double nll = 0;                    ///< negative log-likelihood of the answers under the fitted curve
  int iterations = 0;
  std::string warning;  ///< empty when the plain fit is fine

  /// P(yes | x) of the fitted model.
  double probability(double x) const;
  /// x where the underlying F equals p, 0 < p < 1 (see header comment); NaN when slope == 0.
  double threshold(double p) const;
};

/// x and y (0 or 1) of one participant and condition, same length >= 2.
/// Throws InputError for mismatched lengths, non-finite x, y not 0/1, fewer than 2 distinct x,
/// or invalid guess/lapse.
PsychometricFit fit_psychometric(const std::vector<double>& x, const std::vector<double>& y,
                                 const PsychometricOptions& options = {});

/// Firth's penalised-likelihood logistic fit (plain model), whatever the data.
PsychometricFit fit_logistic_firth(const std::vector<double>& x, const std::vector<double>& y,
                                   int max_iterations = 200);

/// True when the answers are completely or quasi-completely separated by x (or all equal).
bool is_separated(const std::vector<double>& x, const std::vector<double>& y);

/// Parametric-bootstrap percentile intervals of thresholds: answers are redrawn from the fitted model
/// at the same x, refitted the same way, replicate b seeded with derive_seed(seed, "bootstrap/<b>").
struct ThresholdInterval {
  double p = 0, lower = 0, upper = 0;
  int replicates_used = 0;  ///< replicates with a finite threshold
};
std::vector<ThresholdInterval> bootstrap_thresholds(const std::vector<double>& x, const PsychometricFit& fit,
                                                    const std::vector<double>& probabilities, int replicates,
                                                    std::uint64_t seed,
                                                    const PsychometricOptions& options = {},
                                                    double level = 0.95);

}  // namespace crowdlab::analysis
