#pragma once
// Linear mixed models as lme4::lmer fits them (Bates, Maechler, Bolker & Walker 2015, "Fitting Linear
// Mixed-Effects Models Using lme4", J. Stat. Softw. 67(1), section 3): y = X beta + Z Lambda_theta u + e,
// u ~ N(0, sigma^2 I), e ~ N(0, sigma^2 I). For a given theta (the lower-triangular relative
// covariance factors of the random terms, column-wise as lme4's theta) the penalised least squares
// problem is solved through the sparse Cholesky factor L of Lambda' Z'Z Lambda + I (Eigen's
// SimplicialLLT, its fill-reducing ordering analysed once) and the dense factor R_X of
// X'X - R_ZX' R_ZX; beta and sigma are profiled out and the profiled deviance (eq. 34 for ML, eq. 41
// for REML) is minimised over theta by NLopt's BOBYQA (Powell 2009) with lme4's bounds (diagonal of
// each factor >= 0) and start (identity), the optimiser lme4's default nloptwrap uses for lmer.
// Every per-theta step uses only the cross-products Z'Z, Z'X, Z'y, X'X, X'y, y'y, so its cost does
// not grow with the number of rows.
// Outputs as lme4: fixed effects with vcov = sigma^2 (R_X' R_X)^-1, random-effect SDs and correlations
// (VarCorr), the residual SD, REMLcrit or deviance, and lme4's singularity check (a diagonal theta
// element below 1e-4: isSingular's default tolerance) as a warning, and lmerTest's Satterthwaite df and
// p of each fixed effect (satterthwaite.hpp).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/lmm_formula.hpp"
#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

struct LmmFixed {
  std::string term;
  double estimate = 0, se = 0, t = 0;
  double df = 0, p = 0;  ///< Satterthwaite df and two-sided p, as lmerTest (satterthwaite.hpp)
};

struct LmmRandomSd {
  std::string group, term;
  double sd = 0;
};

struct LmmRandomCorr {
  std::string group, term1, term2;
  double corr = 0;
};

struct LmmResult {
  std::vector<LmmFixed> fixed;
  std::vector<LmmRandomSd> random_sd;
  std::vector<LmmRandomCorr> random_corr;
  double residual_sd = 0;
  double criterion = 0;  ///< REML criterion (reml) or deviance (-2 log-likelihood, ML)
  bool reml = true;
  bool converged = false;
  bool singular = false;
  std::vector<double> theta;
  int evaluations = 0;
  size_t observations = 0;
  std::vector<std::string> warnings;
};

/// The size of model fit_lmm takes on, checked before the fit. The optimiser searches the random terms'
/// covariance parameters (q (q + 1) / 2 for a term of q effects per level): its evaluations grow with their
/// square, so `(stimulus | participant)` with 30 stimuli (465 parameters) ran for hours (issue 33).
struct LmmLimits {
  std::size_t max_covariance_parameters =
      55;  ///< 10 correlated effects per level; `--max-covariance-parameters`
};

/// Throws InputError (exit 2): formula errors, missing columns, empty or non-finite cells (file:line),
/// a constant response, a grouping factor with one level or as many levels as rows, a rank-deficient
/// fixed-effect model matrix, more random effects per level than a group can identify, random terms with
/// more covariance parameters than `limits` allows (the count, the limit and the option that raises it).
LmmResult fit_lmm(const CsvTable& table, const std::string& formula, bool reml = true,
                  const LmmLimits& limits = {});

/// {"fixed": [{term, estimate, se, t, df, p}], "random": [{group, term, sd} | {group, term1, term2, corr}],
///  "residual_sd", "reml_criterion" | "deviance", "converged", "singular", "warnings", "observations"}.
nlohmann::json lmm_to_json(const LmmResult& result);

}  // namespace crowdlab::analysis
