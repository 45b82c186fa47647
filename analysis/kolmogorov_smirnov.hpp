#pragma once
// The one-sample Kolmogorov-Smirnov test and the Kolmogorov distribution (Boost 1.74 has neither).
// - Exact P(D_n < d): Marsaglia, Tsang & Wang (2003), "Evaluating Kolmogorov's distribution",
//   J. Stat. Softw. 8(18): the (k,k) entry of H^n (H the m x m matrix of their eq. in section 2,
//   m = 2k - 1, k = floor(n d) + 1, h = k - n d) times n!/n^n, with exponent tracking against overflow.
// - Asymptotic P(sqrt(n) D_n <= x) = 1 - 2 sum_{j>=1} (-1)^(j-1) exp(-2 j^2 x^2)  (Kolmogorov 1933),
//   evaluated for x < 1 with the equivalent theta-function form
//   sqrt(2 pi)/x sum_{j>=1} exp(-(2j-1)^2 pi^2 / (8 x^2)), which converges fast there.
// ks_test follows R's ks.test for a continuous, fully specified null: exact p for n < 100, else asymptotic.
#include <functional>
#include <vector>

namespace crowdlab::analysis {

/// P(D_n < d), exact, n >= 1.
double kolmogorov_cdf_exact(int n, double d);
/// Limiting P(sqrt(n) D_n <= x).
double kolmogorov_cdf_asymptotic(double x);

struct KsResult {
  double statistic = 0;  ///< D = sup |F_n - F|
  double p = 1;          ///< two-sided
  bool exact = false;
};
/// Two-sided one-sample test of `sample` against the continuous CDF `cdf`. exact: -1 = R's default
/// (exact when n < 100), 0 = asymptotic, 1 = exact. Throws InputError on an empty or non-finite sample.
KsResult ks_test(std::vector<double> sample, const std::function<double(double)>& cdf, int exact = -1);

/// Normality of residuals: KS of the standardised values against N(0, 1), plus Q-Q plot data.
/// Note the p value is conservative because mean and SD are estimated (Lilliefors 1967); the papers
/// use it, with Q-Q plots, as a screening check.
struct NormalityCheck {
  KsResult ks;
  std::vector<double> theoretical;  ///< N(0,1) quantiles at R's ppoints(n)
  std::vector<double> sample;       ///< sorted standardised values
};
NormalityCheck normality_check(const std::vector<double>& values);

}  // namespace crowdlab::analysis
