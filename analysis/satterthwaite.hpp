#pragma once
// Satterthwaite (1946) degrees of freedom for the t tests of a linear mixed model's fixed effects, as
// lmerTest computes them (Kuznetsova, Brockhoff & Christensen 2017, "lmerTest Package: Tests in Linear
// Mixed Effects Models", J. Stat. Softw. 82(13), section 3.1; lmerTest's as_lmerModLmerTest and
// contest1D):
//   varpar = (theta, sigma): the model's variance parameters at the optimum;
//   A = 2 H^+ (their asymptotic covariance), H the Hessian of the deviance (REML or ML, not profiled)
//       in varpar, H^+ its pseudo-inverse over the eigenvalues above 1e-8 (lmerTest's tolerance; a
//       negative eigenvalue below -1e-8 is reported as lmerTest warns "Model failed to converge");
//   for fixed effect j, v = C_jj with C = vcov(beta)(varpar), g = dv / dvarpar, df_j = 2 v^2 / (g' A g).
// Inputs: the deviance and vcov(beta) as functions of varpar, the optimum, and per coordinate the scale
// of its finite-difference steps. Derivatives are Boost.Math's 6th-order central finite differences
// (finite_difference_derivative) on x_k + scale_k * t, nested for the Hessian; lmerTest uses numDeriv's
// Richardson extrapolation. Both approximate the same derivatives of a smooth function to ~1e-7.
// Output: df per fixed effect (NaN where g' A g is not positive) and warnings.
#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace crowdlab::analysis {

using VarparFunction = std::function<double(const std::vector<double>&)>;
using VarparMatrixFunction = std::function<Eigen::MatrixXd(const std::vector<double>&)>;

struct SatterthwaiteResult {
  std::vector<double> df;  ///< per fixed effect (diagonal element of vcov(beta))
  std::vector<std::string> warnings;
};

SatterthwaiteResult satterthwaite_df(const VarparFunction& deviance, const VarparMatrixFunction& vcov_beta,
                                     const std::vector<double>& varpar,
                                     const std::vector<double>& step_scale);

/// Two-sided p of a t statistic with (possibly fractional) df; NaN when df is not positive.
double t_test_p(double t, double df);

}  // namespace crowdlab::analysis
