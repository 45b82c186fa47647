#pragma once
// Psychometric function with a FITTED symmetric lapse rate (issue 20; Wichmann & Hill 2001a, Vision
// Research 63(8); Prins 2012, J. Vision 12(6):25):
//   P(yes | x) = lambda + (1 - 2 lambda) F(intercept + slope x),   F logistic,   0 <= lambda < 0.5,
// i.e. guess = lapse = lambda: a lapse gives a random answer either way, which is what a 2-answer task
// whose "yes" rate falls from ~1 to ~0 (P(collision) over distance) implies at both ends.
// Maximum likelihood over (intercept, slope, lambda) by NLopt's SLSQP (Kraft 1988) with the analytic
// gradient and the bound constraints 0 <= lambda <= kMaxLapse; internally x is standardised (z = (x -
// mean) / sd) so intercept and slope are not collinear, and the estimate is mapped back. Two starts
// (the plain logistic fit with lambda = 0.01 and with lambda = 0.1); the better likelihood wins.
// Boundary lambda = 0: an estimate on the bound is reported as exactly 0 with lapse_at_boundary set;
// the curve is then the plain logistic fit (the likelihood ratio against it is 0, and the usual
// chi-square reference for testing lambda = 0 does not apply on a boundary: Self & Liang 1987).
// Separation up to lapses: when a step between two adjacent x levels, with the contrary answers as
// lapses, fits as well as the fitted curve (best_step), the ML slope is infinite; the estimate where the
// optimiser stopped is kept with step_not_identified and a warning naming the interval. A slope at its
// bound (|slope| * sd(x) = kMaxStandardSlope) is warned about too.
#include <cmath>
#include <vector>

#include "analysis/psychometric_fit.hpp"

namespace crowdlab::analysis {

inline constexpr double kMaxLapse = 0.5 - 1e-6;
inline constexpr double kMaxStandardSlope = 1e3;

/// Fits the symmetric-lapse model; x, y validated by the caller (fit_psychometric). Sets intercept,
/// slope, guess = lapse = lambda, lapse_fitted, lapse_at_boundary, nll, converged and warning.
PsychometricFit fit_symmetric_lapse(const std::vector<double>& x, const std::vector<double>& y,
                                    const PsychometricFit& plain);

/// The model's limits as |slope| grows without bound: a step between two adjacent x levels, or at one
/// level (which keeps its own answer rate), the contrary answers elsewhere counted as lapses at their ML
/// rate. `below`/`above` bracket the step. When the best limit's likelihood is as high as the fitted
/// curve's, the ML slope is infinite (separation up to lapses).
struct StepSplit {
  double below = 0, above = 0;
  double nll = INFINITY;
};
StepSplit best_step(const std::vector<double>& x, const std::vector<double>& y);

/// Negative log-likelihood of the binary answers under a fit's curve (its guess and lapse included).
double psychometric_nll(const std::vector<double>& x, const std::vector<double>& y,
                        const PsychometricFit& fit);

}  // namespace crowdlab::analysis
