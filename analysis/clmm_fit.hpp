#pragma once
// Cumulative link mixed model with random intercepts, as ordinal::clmm (Christensen 2019, "A Tutorial
// on fitting Cumulative Link Mixed Models with clmm2 from the ordinal Package"; Agresti 2010,
// Analysis of Ordinal Categorical Data, ch. 10):
//   P(Y_i <= k | b) = F(theta_k - x_i' beta - b_g(i)),   b_g ~ N(0, sd_g^2),   F logistic or normal,
// flexible thresholds theta_1 < ... < theta_{K-1} (named "1|2", ...), fixed effects without an
// intercept (R's coding, as clmm drops the intercept column), one or more random-intercept terms
// (1 | g) for distinct grouping factors (several give crossed effects, e.g. participants and stimuli),
// the random effects integrated out by the Laplace approximation (clmm's default nAGQ = 1): per group
// in closed form for one term, jointly through a sparse Cholesky factor for several.
// The marginal log-likelihood is maximised by NLopt's BOBYQA over (theta_1, log increments of the
// thresholds, beta, log sd of each term), finished by Newton steps on its finite-difference gradient
// and Hessian (docs/analysis.md); standard errors come from the inverse of the negative Hessian of the
// Laplace log-likelihood in (theta, beta, log sd), by central differences, the quantity clmm's Hess =
// TRUE approximates (clmm's own differences carry up to ~1 % of numerical noise: docs/analysis.md).
// Response levels: sorted numerically when every level is a number, else in byte order.
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

struct ClmmCoefficient {
  std::string name;
  double estimate = 0, se = 0, z = 0, p = 0;
};

struct ClmmRandomIntercept {
  std::string group;
  double sd = 0;
  size_t levels = 0;
};

struct ClmmResult {
  std::string link;
  std::vector<ClmmCoefficient> thresholds, fixed;
  std::vector<ClmmRandomIntercept> random;  ///< one per (1 | group) term, in formula order
  double loglik = 0;
  bool converged = false;
  size_t observations = 0;
  std::vector<std::string> warnings;
};

/// `link`: "logit" or "probit". Throws InputError (exit 2) for formula errors, missing columns, empty or
/// non-finite cells, fewer than 3 response levels, a grouping factor with one level, no random term, a
/// random slope, a grouping factor in two terms, or a rank-deficient fixed-effects matrix.
/// Columns named in `categorical` are factors even when their cells are numbers (R's factor(x)).
ClmmResult fit_clmm(const CsvTable& table, const std::string& formula, const std::string& link = "logit",
                    const std::set<std::string>& categorical = {});

/// {"thresholds": [{name, estimate, se}], "fixed": [{term, estimate, se, z, p}], "random": [{group, sd}],
///  "loglik", "link", "converged", "observations", "warnings"}.
nlohmann::json clmm_to_json(const ClmmResult& result);

}  // namespace crowdlab::analysis
