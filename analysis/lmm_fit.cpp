#include "analysis/lmm_fit.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "analysis/model_matrix.hpp"
#include "analysis/model_not_fitted.hpp"
#include "analysis/nlopt_minimise.hpp"
#include "analysis/satterthwaite.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
using SpMat = Eigen::SparseMatrix<double>;
constexpr double kSingularTolerance = 1e-4;  // lme4::isSingular's default tol
constexpr double kTwoPi = 6.283185307179586476925286766559;

struct RandomBlock {
  std::string group;
  std::vector<std::string> names;  ///< column names of the term ("(Intercept)", "b", ...)
  Eigen::Index q = 0, levels = 0, offset = 0, theta_offset = 0;
  std::vector<size_t> codes;  ///< level of each row
};

struct Problem {
  Eigen::MatrixXd xtx, ztx;
  Eigen::VectorXd xty, zty;
  SpMat ztz;
  double yty = 0;
  Eigen::Index n = 0, p = 0, q = 0;
  bool reml = true;
  std::vector<RandomBlock> blocks;
  std::vector<bool> diagonal;  ///< per theta element: on a factor's diagonal (bounded below by 0)
  int evaluations = 0;
};

// What one theta gives: the profiled deviance and what the final estimates need.
struct Profile {
  double deviance = INFINITY, r2 = 0;
  double logdet_l = 0, logdet_rx = 0;  ///< log det(L L'), log det(R_X' R_X)
  Eigen::VectorXd beta;
  Eigen::MatrixXd rxtrx;
};

SpMat lambda_of(const Problem& pr, const double* theta) {
  std::vector<Eigen::Triplet<double>> t;
  for (const auto& b : pr.blocks)
    for (Eigen::Index l = 0; l < b.levels; ++l) {
      Eigen::Index k = b.theta_offset;
      for (Eigen::Index j = 0; j < b.q; ++j)
        for (Eigen::Index i = j; i < b.q; ++i)
          t.emplace_back(b.offset + l * b.q + i, b.offset + l * b.q + j, theta[k++]);
    }
  SpMat lambda(pr.q, pr.q);
  lambda.setFromTriplets(t.begin(), t.end());
  return lambda;
}

Profile profile(const Problem& pr, const double* theta) {
  Profile out;
  const SpMat lambda = lambda_of(pr, theta);
  const SpMat lt = lambda.transpose();
  SpMat identity(pr.q, pr.q);
  identity.setIdentity();
  const SpMat a = SpMat(lt * pr.ztz * lambda) + identity;
  Eigen::SimplicialLDLT<SpMat> ldlt(a);
  if (ldlt.info() != Eigen::Success) return out;
  const Eigen::VectorXd d_sqrt = ldlt.vectorD().cwiseSqrt();
  // c_u = D^-1/2 L^-1 P Lambda' Z'y and R_ZX likewise: the blocks of the augmented Cholesky factor.
  const Eigen::VectorXd cu =
      (ldlt.matrixL().solve(ldlt.permutationP() * (lt * pr.zty))).cwiseQuotient(d_sqrt);
  const Eigen::MatrixXd rzx = d_sqrt.cwiseInverse().asDiagonal() *
                              Eigen::MatrixXd(ldlt.matrixL().solve(ldlt.permutationP() * (lt * pr.ztx)));
  out.rxtrx = pr.xtx - rzx.transpose() * rzx;
  const Eigen::LLT<Eigen::MatrixXd> rx(out.rxtrx);
  if (rx.info() != Eigen::Success) return out;
  const Eigen::VectorXd rhs = pr.xty - rzx.transpose() * cu;
  const Eigen::VectorXd cb = rx.matrixL().solve(rhs);
  out.beta = rx.solve(rhs);
  out.r2 = pr.yty - cu.squaredNorm() - cb.squaredNorm();
  if (!(out.r2 > 0)) return out;
  out.logdet_l = ldlt.vectorD().array().log().sum();
  out.logdet_rx = 2.0 * rx.matrixLLT().diagonal().array().log().sum();
  const auto n = static_cast<double>(pr.n), p = static_cast<double>(pr.p);
  if (pr.reml)
    out.deviance = out.logdet_l + out.logdet_rx + (n - p) * (1.0 + std::log(kTwoPi * out.r2 / (n - p)));
  else
    out.deviance = out.logdet_l + n * (1.0 + std::log(kTwoPi * out.r2 / n));
  return out;
}

// The deviance at (theta, sigma) without profiling sigma out (lmerTest's devfun_vp): ML
// log det(L L') + pwrss / sigma^2 + n log(2 pi sigma^2); REML adds log det(R_X' R_X) - p log(2 pi sigma^2).
double deviance_at(const Problem& pr, const std::vector<double>& varpar) {
  const Profile at = profile(pr, varpar.data());
  const double sigma2 = varpar.back() * varpar.back();
  const auto n = static_cast<double>(pr.n), p = static_cast<double>(pr.p);
  const double ml = at.logdet_l + at.r2 / sigma2 + n * std::log(kTwoPi * sigma2);
  return pr.reml ? ml + at.logdet_rx - p * std::log(kTwoPi * sigma2) : ml;
}

// vcov(beta) = sigma^2 (R_X' R_X)^-1 at (theta, sigma).
Eigen::MatrixXd vcov_at(const Problem& pr, const std::vector<double>& varpar) {
  return varpar.back() * varpar.back() * profile(pr, varpar.data()).rxtrx.inverse();
}

// Satterthwaite df of each fixed effect (satterthwaite.hpp) at the optimum; theta steps scaled by
// max(|theta|, 0.01) (theta is relative to sigma, so unit-free), sigma's by sigma itself.
SatterthwaiteResult fixed_effect_df(const Problem& pr, const std::vector<double>& theta, double sigma) {
  std::vector<double> varpar = theta, scale;
  varpar.push_back(sigma);
  for (double v : theta) scale.push_back(std::max(std::abs(v), 0.01));
  scale.push_back(sigma);
  return satterthwaite_df([&](const std::vector<double>& v) { return deviance_at(pr, v); },
                          [&](const std::vector<double>& v) { return vcov_at(pr, v); }, varpar, scale);
}

double lmm_objective(unsigned, const double* theta, double*, void* data) {
  auto& pr = *static_cast<Problem*>(data);
  ++pr.evaluations;
  return profile(pr, theta).deviance;
}

[[noreturn]] void refuse(const CsvTable& table, const std::string& why) {
  throw InputError(table.source + ": " + why);
}

std::vector<std::string> variables_of(const LmmFormula& f) {
  std::vector<std::string> names = {f.response};
  for (const auto& t : f.fixed) names.insert(names.end(), t.begin(), t.end());
  for (const auto& r : f.random)
    for (const auto& t : r.terms) names.insert(names.end(), t.begin(), t.end());
  return names;
}

RandomBlock random_block(const CsvTable& table, const RandomTerm& term, const ModelMatrix& zk) {
  RandomBlock b;
  b.group = term.group;
  b.names = zk.names;
  b.q = zk.x.cols();
  std::vector<std::string> levels;
  b.codes = grouping_codes(table, term.group, levels);
  b.levels = static_cast<Eigen::Index>(levels.size());
  const auto n = static_cast<Eigen::Index>(table.rows.size());
  if (b.levels < 2)
    refuse(table, "grouping factor '" + term.group + "' has a single level; a random effect needs >= 2");
  if (b.levels * b.q >= n)
    refuse(table, "the random term for '" + term.group + "' has " + std::to_string(b.levels * b.q) +
                      " effects for " + std::to_string(n) + " observations: unidentifiable (lme4's check)");
  return b;
}

Problem build_problem(const CsvTable& table, const LmmFormula& f, bool reml, const LmmLimits& limits,
                      std::vector<std::string>& fixed_names) {
  const auto vars = read_model_variables(table, variables_of(f));
  const auto& yv = vars.at(f.response);
  if (!yv.numeric) refuse(table, "the response '" + f.response + "' is not numeric");
  const size_t n = table.rows.size();
  const Eigen::Map<const Eigen::VectorXd> y(yv.values.data(), static_cast<Eigen::Index>(n));
  if (n < 3 || (y.array() - y.mean()).abs().maxCoeff() == 0.0)
    refuse(table, "the response '" + f.response + "' is constant (or has < 3 rows): nothing to model");
  const ModelMatrix x = model_matrix(f.fixed, f.intercept, vars, n);
  fixed_names = x.names;
  if (x.x.cols() == 0) refuse(table, "the fixed-effects part is empty");
  if (Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(x.x).rank() < x.x.cols() ||
      x.x.cols() >= static_cast<Eigen::Index>(n))
    refuse(table,
           "the fixed-effects model matrix is rank deficient (a level combination is missing or "
           "two predictors are collinear); crowdlab does not drop columns as lme4 does");
  Problem pr;
  pr.reml = reml;
  pr.n = static_cast<Eigen::Index>(n);
  pr.p = x.x.cols();
  std::vector<Eigen::Triplet<double>> zt;
  std::vector<ModelMatrix> zks;
  for (const auto& term : f.random) {
    ModelMatrix zk = model_matrix(term.terms, term.intercept, vars, n);
    RandomBlock b = random_block(table, term, zk);
    const auto parameters = pr.diagonal.size() + static_cast<size_t>(b.q * (b.q + 1) / 2);
    if (parameters > limits.max_covariance_parameters)
      refuse(table, "the random terms have " + std::to_string(parameters) +
                        " covariance parameters (the term for '" + term.group + "' has " +
                        std::to_string(b.q) + " effects per level, " + std::to_string(b.q * (b.q + 1) / 2) +
                        " parameters), more than the limit of " +
                        std::to_string(limits.max_covariance_parameters) +
                        ": the fit's work grows with their square; a random slope of a many-level factor is "
                        "rarely identifiable (raise with --max-covariance-parameters)");
    b.offset = pr.q;
    b.theta_offset = static_cast<Eigen::Index>(pr.diagonal.size());
    for (Eigen::Index j = 0; j < b.q; ++j)
      for (Eigen::Index i = j; i < b.q; ++i) pr.diagonal.push_back(i == j);
    for (size_t r = 0; r < n; ++r)
      for (Eigen::Index c = 0; c < b.q; ++c)
        zt.emplace_back(static_cast<Eigen::Index>(r),
                        b.offset + static_cast<Eigen::Index>(b.codes[r]) * b.q + c,
                        zk.x(static_cast<Eigen::Index>(r), c));
    pr.q += b.levels * b.q;
    pr.blocks.push_back(std::move(b));
  }
  SpMat z(pr.n, pr.q);
  z.setFromTriplets(zt.begin(), zt.end());
  pr.xtx = x.x.transpose() * x.x;
  pr.xty = x.x.transpose() * y;
  pr.ztx = z.transpose() * x.x;
  pr.zty = z.transpose() * y;
  pr.ztz = SpMat(z.transpose() * z);
  pr.yty = y.squaredNorm();
  return pr;
}

void fill_random(const Problem& pr, const std::vector<double>& theta, double sigma, LmmResult& out) {
  for (const auto& b : pr.blocks) {
    Eigen::MatrixXd t = Eigen::MatrixXd::Zero(b.q, b.q);
    Eigen::Index k = b.theta_offset;
    for (Eigen::Index j = 0; j < b.q; ++j)
      for (Eigen::Index i = j; i < b.q; ++i) t(i, j) = theta[static_cast<size_t>(k++)];
    const Eigen::MatrixXd cov = sigma * sigma * t * t.transpose();
    for (Eigen::Index i = 0; i < b.q; ++i)
      out.random_sd.push_back({b.group, b.names[static_cast<size_t>(i)], std::sqrt(cov(i, i))});
    for (Eigen::Index i = 0; i < b.q; ++i)
      for (Eigen::Index j = i + 1; j < b.q; ++j) {
        const double denom = std::sqrt(cov(i, i) * cov(j, j));
        out.random_corr.push_back({b.group, b.names[static_cast<size_t>(i)], b.names[static_cast<size_t>(j)],
                                   denom > 0 ? cov(i, j) / denom : std::nan("")});
      }
  }
}
}  // namespace

LmmResult fit_lmm(const CsvTable& table, const std::string& formula, bool reml, const LmmLimits& limits) {
  require_columns(table, formula_variable_names(formula), "the formula");
  const LmmFormula f = parse_lmm_formula(formula);
  std::vector<std::string> fixed_names;
  Problem pr = build_problem(table, f, reml, limits, fixed_names);
  const auto m = static_cast<unsigned>(pr.diagonal.size());
  std::vector<double> theta(m), lower(m);
  for (unsigned k = 0; k < m; ++k) {
    theta[k] = pr.diagonal[k] ? 1.0 : 0.0;  // lme4's start: identity factors
    lower[k] = pr.diagonal[k] ? 0.0 : -HUGE_VAL;
  }
  const NloptOutcome opt = minimise_derivative_free(theta, lower, lmm_objective, &pr, 100000);
  LmmResult out;
  out.reml = reml;
  out.observations = static_cast<size_t>(pr.n);
  out.evaluations = pr.evaluations;
  out.converged = opt.converged();
  if (!out.converged)
    out.warnings.push_back("the optimiser did not converge (NLopt status " + std::to_string(opt.status) +
                           ")");
  for (unsigned k = 0; k < m; ++k)
    if (pr.diagonal[k] && theta[k] < 1e-10) theta[k] = 0.0;  // on the bound, as lme4 reports it
  const Profile fin = profile(pr, theta.data());
  if (!std::isfinite(fin.deviance))
    refuse(table, "the mixed model could not be fitted (singular cross-products)");
  out.theta = theta;
  out.criterion = fin.deviance;
  const double dof = static_cast<double>(reml ? pr.n - pr.p : pr.n);
  out.residual_sd = std::sqrt(fin.r2 / dof);
  const Eigen::MatrixXd vcov = out.residual_sd * out.residual_sd * fin.rxtrx.inverse();
  const SatterthwaiteResult satterthwaite = fixed_effect_df(pr, theta, out.residual_sd);
  for (Eigen::Index j = 0; j < pr.p; ++j) {
    const double se = std::sqrt(vcov(j, j)), t = fin.beta[j] / se;
    const double df = satterthwaite.df[static_cast<size_t>(j)];
    const std::string& term = fixed_names[static_cast<size_t>(j)];
    require_finite_estimate(fin.beta[j], "the estimate of " + term);
    if (!(se > 0) || !std::isfinite(se))
      throw ModelNotFitted(table.source + ": the standard error of " + term +
                           " is not a positive finite number (residual variance 0: the model fits the data "
                           "exactly)");
    out.fixed.push_back({fixed_names[static_cast<size_t>(j)], fin.beta[j], se, t, df, t_test_p(t, df)});
  }
  out.warnings.insert(out.warnings.end(), satterthwaite.warnings.begin(), satterthwaite.warnings.end());
  fill_random(pr, theta, out.residual_sd, out);
  for (unsigned k = 0; k < m; ++k)
    out.singular = out.singular || (pr.diagonal[k] && theta[k] < kSingularTolerance);
  if (out.singular)
    out.warnings.push_back(
        "boundary (singular) fit: see help('isSingular') in lme4; a variance is (near) zero or a correlation "
        "is +-1");
  return out;
}

nlohmann::json lmm_to_json(const LmmResult& r) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json fixed = nlohmann::json::array(), random = nlohmann::json::array();
  for (const auto& f : r.fixed)
    fixed.push_back({{"term", f.term},
                     {"estimate", f.estimate},
                     {"se", num(f.se)},
                     {"t", num(f.t)},
                     {"df", num(f.df)},
                     {"p", num(f.p)}});
  for (const auto& s : r.random_sd)
    random.push_back({{"group", s.group}, {"term", s.term}, {"sd", num(s.sd)}});
  for (const auto& c : r.random_corr)
    random.push_back({{"group", c.group}, {"term1", c.term1}, {"term2", c.term2}, {"corr", num(c.corr)}});
  nlohmann::json j = {{"fixed", fixed},
                      {"random", random},
                      {"residual_sd", r.residual_sd},
                      {"converged", r.converged},
                      {"singular", r.singular},
                      {"warnings", r.warnings},
                      {"observations", r.observations}};
  j[r.reml ? "reml_criterion" : "deviance"] = r.criterion;
  return j;
}

}  // namespace crowdlab::analysis
