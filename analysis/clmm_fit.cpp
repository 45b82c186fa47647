#include "analysis/clmm_fit.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>

#include "analysis/lmm_formula.hpp"
#include "analysis/model_matrix.hpp"
#include "analysis/model_not_fitted.hpp"
#include "analysis/nlopt_minimise.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
struct Link {
  bool logit = true;
  double cdf(double t) const {
    if (logit) return t >= 0 ? 1.0 / (1.0 + std::exp(-t)) : std::exp(t) / (1.0 + std::exp(t));
    return 0.5 * std::erfc(-t / std::sqrt(2.0));
  }
  double pdf(double t) const {
    if (logit) {
      const double f = cdf(t);
      return f * (1.0 - f);
    }
    return std::exp(-0.5 * t * t) / std::sqrt(2.0 * M_PI);
  }
  // d pdf / dt (the second derivative of the cdf)
  double dpdf(double t) const {
    if (logit) {
      const double f = cdf(t);
      return f * (1.0 - f) * (1.0 - 2.0 * f);
    }
    return -t * pdf(t);
  }
  // d2 pdf / dt2 (the third derivative of the cdf), for the gradient of the Laplace curvature term
  double ddpdf(double t) const {
    if (logit) {
      const double f = cdf(t);
      return f * (1.0 - f) * (1.0 - 6.0 * f + 6.0 * f * f);
    }
    return (t * t - 1.0) * pdf(t);
  }
};

// One random-intercept term (1 | group): its levels and each row's level.
struct InterceptTerm {
  std::string group;
  std::vector<std::string> levels;           ///< in order of first appearance
  std::vector<size_t> code;                  ///< level of each row
  std::vector<std::vector<size_t>> rows_of;  ///< rows of each level
  size_t offset = 0;                         ///< first index of its effects in u
};

struct Data {
  Link link;
  Eigen::MatrixXd x;   ///< rows x fixed effects (no intercept)
  std::vector<int> y;  ///< response level 0..K-1
  std::vector<InterceptTerm> terms;
  size_t q = 0;  ///< random effects in all
  int levels = 0;
  mutable std::vector<double> modes;  ///< the last conditional modes: Newton's next start
};

// Parameters in the natural space: thresholds (K-1), beta (p), log sd of each random term.
struct Params {
  std::vector<double> theta;
  Eigen::VectorXd beta;
  std::vector<double> log_sd;
};

Params unpack_natural(const Data& d, const double* v) {
  Params p;
  const auto k1 = static_cast<size_t>(d.levels - 1), np = static_cast<size_t>(d.x.cols());
  p.theta.assign(v, v + k1);
  p.beta = Eigen::Map<const Eigen::VectorXd>(v + k1, d.x.cols());
  p.log_sd.assign(v + k1 + np, v + k1 + np + d.terms.size());
  return p;
}

// F, F' and F'' at t (F' = pdf, F'' its derivative); t = +-inf at the open ends of the scale. One exp
// per call for the logit link.
struct LinkValues {
  double cdf = 0, pdf = 0, dpdf = 0;
};
LinkValues link_values(const Link& link, double t) {
  if (!std::isfinite(t)) return {t > 0 ? 1.0 : 0.0, 0.0, 0.0};
  if (link.logit) {
    const double f = link.cdf(t), g = f * (1.0 - f);
    return {f, g, g * (1.0 - 2.0 * f)};
  }
  const double g = link.pdf(t);
  return {link.cdf(t), g, -t * g};
}

// log P(y | eta + b) and its first two derivatives in b.
void row_terms(const Data& d, const Params& p, int y, double eta, double b, double& logp, double& d1,
               double& d2) {
  const double upper = y < d.levels - 1 ? p.theta[static_cast<size_t>(y)] - eta - b : HUGE_VAL;
  const double lower = y > 0 ? p.theta[static_cast<size_t>(y - 1)] - eta - b : -HUGE_VAL;
  const LinkValues u = link_values(d.link, upper), l = link_values(d.link, lower);
  const double prob = std::max(u.cdf - l.cdf, 1e-300);
  logp = std::log(prob);
  const double dp = -(u.pdf - l.pdf);  // d prob / db
  const double ddp = u.dpdf - l.dpdf;  // d2 prob / db2
  d1 = dp / prob;
  d2 = ddp / prob - d1 * d1;
}

// Laplace approximation of the marginal log-likelihood (clmm's nAGQ = 1), on u = b / sd ~ N(0, 1):
// each group's conditional mode by Newton's method converged to rounding (|step| < 1e-12), the
// curvature taken at that mode. Newton starts from the modes of the previous call (d.modes), which
// changes the value by far less than rounding and saves most iterations in the optimiser's and the
// Hessian's nearby evaluations.
double laplace_loglik_nested(const Data& d, const Params& p) {
  const Eigen::VectorXd eta = d.x * p.beta;
  const double sd = std::exp(p.log_sd[0]);
  const auto& term = d.terms[0];
  // Sums in long double (as R's sum()): the Hessian's second differences divide rounding noise in the
  // sum of ~1000 rows by 1e-8; in double it reached 1e-4 of the crossed model's SEs.
  long double total = 0;
  d.modes.resize(d.q, 0.0);
  for (size_t g = 0; g < term.rows_of.size(); ++g) {
    const auto& rows = term.rows_of[g];
    double u = std::isfinite(d.modes[g]) ? d.modes[g] : 0.0;
    for (int it = 0; it < 50; ++it) {
      double grad = -u, h = -1.0;
      for (size_t r : rows) {
        double lp = 0, d1 = 0, d2 = 0;
        row_terms(d, p, d.y[r], eta[static_cast<Eigen::Index>(r)], sd * u, lp, d1, d2);
        grad += sd * d1;
        h += sd * sd * d2;
      }
      // The log-posterior is strictly concave (h <= -1); a bounded step keeps Newton from overshooting
      // where its curvature changes fast (far from the mode, or from a poor warm start).
      const double step = std::clamp(-grad / h, -2.0, 2.0);
      u += step;
      if (std::abs(step) < 1e-12) break;
    }
    d.modes[g] = u;
    // Value and curvature at the mode.
    long double value_at = -0.5 * u * u;
    double h = -1.0;
    for (size_t r : rows) {
      double lp = 0, d1 = 0, d2 = 0;
      row_terms(d, p, d.y[r], eta[static_cast<Eigen::Index>(r)], sd * u, lp, d1, d2);
      value_at += lp;
      h += sd * sd * d2;
    }
    total += value_at - 0.5L * std::log(-h);
  }
  return static_cast<double>(total);
}

// The same with several random-intercept terms (crossed, e.g. participants and stimuli): the joint
// conditional mode of u = (u_1, ..., u_T) by Newton's method, each step solving the sparse system
// (I + sum_r w_r z_r z_r') step = gradient (Eigen's SimplicialLDLT; z_r holds sd_t at each term's
// level of row r, w_r = -d2 log P), the step bounded to 2 in every coordinate; then
// log L = sum_r log P(y_r | eta_r + z_r'u) - |u|^2 / 2 - log det(I + sum_r w_r z_r z_r') / 2 at the mode.
double laplace_loglik_crossed(const Data& d, const Params& p) {
  const Eigen::VectorXd eta = d.x * p.beta;
  std::vector<double> sd;
  for (double l : p.log_sd) sd.push_back(std::exp(l));
  d.modes.resize(d.q, 0.0);
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(d.modes.data(), static_cast<Eigen::Index>(d.q));
  if (!u.allFinite()) u.setZero();
  const auto q = static_cast<Eigen::Index>(d.q);
  auto index = [&](size_t t, size_t r) {
    return static_cast<Eigen::Index>(d.terms[t].offset + d.terms[t].code[r]);
  };
  // At u: sum of log P, the gradient of the log posterior and the factor of its negative Hessian.
  auto evaluate = [&](long double& loglik, Eigen::VectorXd& grad,
                      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>& ldlt) {
    loglik = 0;
    grad = -u;
    std::vector<Eigen::Triplet<double>> h;
    for (Eigen::Index j = 0; j < q; ++j) h.emplace_back(j, j, 1.0);
    for (size_t r = 0; r < d.y.size(); ++r) {
      double b = 0;
      for (size_t t = 0; t < d.terms.size(); ++t) b += sd[t] * u[index(t, r)];
      double lp = 0, d1 = 0, d2 = 0;
      row_terms(d, p, d.y[r], eta[static_cast<Eigen::Index>(r)], b, lp, d1, d2);
      loglik += lp;
      for (size_t t = 0; t < d.terms.size(); ++t) {
        grad[index(t, r)] += sd[t] * d1;
        for (size_t t2 = 0; t2 < d.terms.size(); ++t2)
          h.emplace_back(index(t, r), index(t2, r), -sd[t] * sd[t2] * d2);
      }
    }
    Eigen::SparseMatrix<double> a(q, q);
    a.setFromTriplets(h.begin(), h.end());
    ldlt.compute(a);
    return ldlt.info() == Eigen::Success;
  };
  long double loglik = 0;
  Eigen::VectorXd grad;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  for (int it = 0; it < 50; ++it) {
    if (!evaluate(loglik, grad, ldlt)) return -HUGE_VAL;
    Eigen::VectorXd step = ldlt.solve(grad);
    const double largest = step.cwiseAbs().maxCoeff();
    if (largest > 2.0) step *= 2.0 / largest;
    u += step;
    if (largest < 1e-12) break;
  }
  if (!evaluate(loglik, grad, ldlt)) return -HUGE_VAL;
  std::copy(u.data(), u.data() + q, d.modes.begin());
  long double log_det = 0;
  for (Eigen::Index j = 0; j < q; ++j) log_det += std::log(ldlt.vectorD()[j]);
  long double u2 = 0;
  for (Eigen::Index j = 0; j < q; ++j) u2 += static_cast<long double>(u[j]) * u[j];
  return static_cast<double>(loglik - 0.5L * u2 - 0.5L * log_det);
}

// log P(y | a) = log(F(U) - F(L)), U = theta_y - a, L = theta_{y-1} - a, and its partial derivatives in
// (U, L) to third order (the mixed ones from P_UL = 0): the chain rule of the analytic gradient below.
struct LogProbDerivatives {
  double logp = 0, u = 0, l = 0, uu = 0, ul = 0, ll = 0, uuu = 0, uul = 0, ull = 0, lll = 0;
  // In b (a = eta + b enters U and L with sign -1): d/db = -(d/dU + d/dL).
  double db1() const { return -(u + l); }
  double db2() const { return uu + 2.0 * ul + ll; }
  double db3() const { return -(uuu + 3.0 * uul + 3.0 * ull + lll); }
};
LogProbDerivatives log_prob_derivatives(const Data& d, const Params& p, int y, double a) {
  auto at = [&](double t, double& f, double& f1, double& f2, double& f3) {
    if (!std::isfinite(t)) {
      f = t > 0 ? 1.0 : 0.0;
      f1 = f2 = f3 = 0;
      return;
    }
    f = d.link.cdf(t);
    f1 = d.link.pdf(t);
    f2 = d.link.dpdf(t);
    f3 = d.link.ddpdf(t);
  };
  double fu = 0, pu = 0, pu2 = 0, pu3 = 0, fl = 0, pl = 0, pl2 = 0, pl3 = 0;
  at(y < d.levels - 1 ? p.theta[static_cast<size_t>(y)] - a : HUGE_VAL, fu, pu, pu2, pu3);
  at(y > 0 ? p.theta[static_cast<size_t>(y - 1)] - a : -HUGE_VAL, fl, pl, pl2, pl3);
  const double prob = std::max(fu - fl, 1e-300);
  // P's partials: P_U = f(U), P_L = -f(L), likewise for the higher orders; log P's follow.
  const double gu = pu / prob, gl = -pl / prob;
  LogProbDerivatives r;
  r.logp = std::log(prob);
  r.u = gu;
  r.l = gl;
  r.uu = pu2 / prob - gu * gu;
  r.ll = -pl2 / prob - gl * gl;
  r.ul = -gu * gl;
  r.uuu = pu3 / prob - 3.0 * (pu2 / prob) * gu + 2.0 * gu * gu * gu;
  r.lll = -pl3 / prob - 3.0 * (-pl2 / prob) * gl + 2.0 * gl * gl * gl;
  r.uul = -(pu2 / prob) * gl + 2.0 * gu * gu * gl;
  r.ull = (pl2 / prob) * gu + 2.0 * gu * gl * gl;
  return r;
}

// Gradient of the one-term Laplace log-likelihood in the natural parameters (thresholds, beta, log sd),
// exact up to the conditional modes' convergence (|step| < 1e-12). Per group, L = l(u*) - log(-h(u*)) / 2
// with l the log posterior, g = dl/du = 0 at the mode u* and h = d2l/du2: by the envelope theorem
// dL/dphi = dl/dphi - (dh/dphi + dh/du du*/dphi) / (2h), and du*/dphi = -(dg/dphi) / h (implicit
// function theorem). Needs the third derivative of log P in b. Returns the log-likelihood.
double laplace_gradient_nested(const Data& d, const Params& p, Eigen::VectorXd& grad) {
  const double value = laplace_loglik_nested(d, p);  // converges d.modes
  const Eigen::VectorXd eta = d.x * p.beta;
  const double sd = std::exp(p.log_sd[0]);
  const auto k1 = static_cast<Eigen::Index>(d.levels - 1), np = d.x.cols();
  const Eigen::Index n = k1 + np + 1, s_index = n - 1;
  grad = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd dl(n), dg(n), dh(n);
  const auto& term = d.terms[0];
  for (size_t g = 0; g < term.rows_of.size(); ++g) {
    const double u = d.modes[g];
    dl.setZero();
    dg.setZero();
    dh.setZero();
    double sum_d1 = 0, sum_d2 = 0, sum_d3 = 0;
    for (size_t r : term.rows_of[g]) {
      const auto ri = static_cast<Eigen::Index>(r);
      const int y = d.y[r];
      const LogProbDerivatives q = log_prob_derivatives(d, p, y, eta[ri] + sd * u);
      const double d1 = q.db1(), d2 = q.db2(), d3 = q.db3();
      sum_d1 += d1;
      sum_d2 += d2;
      sum_d3 += d3;
      if (y < d.levels - 1) {  // theta_y enters U
        dl[y] += q.u;
        dg[y] += -sd * (q.uu + q.ul);
        dh[y] += sd * sd * (q.uuu + 2.0 * q.uul + q.ull);
      }
      if (y > 0) {  // theta_{y-1} enters L
        dl[y - 1] += q.l;
        dg[y - 1] += -sd * (q.ul + q.ll);
        dh[y - 1] += sd * sd * (q.uul + 2.0 * q.ull + q.lll);
      }
      const auto xr = d.x.row(ri).transpose();
      dl.segment(k1, np) += d1 * xr;
      dg.segment(k1, np) += sd * d2 * xr;
      dh.segment(k1, np) += sd * sd * d3 * xr;
    }
    dl[s_index] = sd * u * sum_d1;
    dg[s_index] = sd * sum_d1 + sd * sd * u * sum_d2;
    dh[s_index] = 2.0 * sd * sd * sum_d2 + sd * sd * sd * u * sum_d3;
    const double h = -1.0 + sd * sd * sum_d2, dh_du = sd * sd * sd * sum_d3;
    grad += dl - (dh - dh_du * dg / h) / (2.0 * h);
  }
  return value;
}

double laplace_loglik(const Data& d, const Params& p) {
  return d.terms.size() == 1 ? laplace_loglik_nested(d, p) : laplace_loglik_crossed(d, p);
}

// Optimiser space: theta_1, log(theta_k - theta_{k-1}), beta, log sd of each term.
std::vector<double> to_natural(const Data& d, const double* v) {
  std::vector<double> out(v, v + d.levels - 1 + d.x.cols() + static_cast<Eigen::Index>(d.terms.size()));
  for (int k = 1; k < d.levels - 1; ++k)
    out[static_cast<size_t>(k)] = out[static_cast<size_t>(k - 1)] + std::exp(v[k]);
  return out;
}

double clmm_objective(unsigned, const double* v, double*, void* data) {
  const auto& d = *static_cast<const Data*>(data);
  const auto natural = to_natural(d, v);
  const double ll = laplace_loglik(d, unpack_natural(d, natural.data()));
  return std::isfinite(ll) ? -ll : HUGE_VAL;
}

// The same with its gradient in the optimiser's coordinates (one random term only): by the chain rule,
// theta_k = v_0 + sum_{1 <= j <= k} exp(v_j).
double clmm_objective_with_gradient(unsigned, const double* v, double* grad, void* data) {
  const auto& d = *static_cast<const Data*>(data);
  const auto natural = to_natural(d, v);
  if (!grad) {
    const double ll = laplace_loglik(d, unpack_natural(d, natural.data()));
    return std::isfinite(ll) ? -ll : HUGE_VAL;
  }
  Eigen::VectorXd g;
  const double ll = laplace_gradient_nested(d, unpack_natural(d, natural.data()), g);
  if (!std::isfinite(ll) || !g.allFinite()) return HUGE_VAL;
  const auto k1 = static_cast<Eigen::Index>(d.levels - 1);
  for (Eigen::Index j = 0; j < g.size(); ++j) grad[j] = -g[j];
  double tail = 0;  // sum of dL/dtheta_k for k >= j
  for (Eigen::Index j = k1 - 1; j >= 0; --j) {
    tail += g[j];
    grad[j] = -(j == 0 ? tail : std::exp(v[j]) * tail);
  }
  return -ll;
}

std::vector<std::string> response_levels(const CsvTable& table, size_t col) {
  std::vector<std::string> levels;
  for (size_t r = 0; r < table.rows.size(); ++r) levels.push_back(table.cell(r, col));
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  // Numeric levels are ordered by value. A level strtod reads as a number but that is not a finite double
  // (1e-400, 1e999) is refused here with its row: std::stod threw a bare "stod" (issue 33).
  std::vector<double> values;
  for (const auto& s : levels) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size()) return levels;  // categorical labels: text order
    if (errno == ERANGE || !std::isfinite(v)) {
      size_t r = 0;
      while (table.cell(r, col) != s) ++r;
      (void)table.number(r, col);  // throws file:line:column: column '<response>': not a finite number
    }
    values.push_back(v);
  }
  std::vector<size_t> order(levels.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  std::vector<std::string> sorted;
  for (size_t i : order) sorted.push_back(levels[i]);
  return sorted;
}

Data build_data(const CsvTable& table, const LmmFormula& f, const std::string& link,
                const std::set<std::string>& categorical, std::vector<std::string>& names,
                std::vector<std::string>& levels) {
  if (f.random.empty())
    throw InputError(SourceLocation{"--formula", 0, 0, ""},
                     "clmm needs a random-intercept term (1 | group); for no random effects use an ordinal "
                     "regression (clm)");
  for (const auto& r : f.random)
    if (!r.terms.empty() || !r.intercept)
      throw InputError(SourceLocation{"--formula", 0, 0, ""},
                       "clmm supports random-intercept terms (1 | group) only, not random slopes (group '" +
                           r.group + "')");
  for (size_t i = 0; i < f.random.size(); ++i)
    for (size_t j = i + 1; j < f.random.size(); ++j)
      if (f.random[i].group == f.random[j].group)
        throw InputError(SourceLocation{"--formula", 0, 0, ""},
                         "grouping factor '" + f.random[i].group + "' has two random-intercept terms");
  Data d;
  d.link.logit = link == "logit";
  const size_t ycol = table.column(f.response);
  levels = response_levels(table, ycol);
  for (size_t r = 0; r < table.rows.size(); ++r) {
    if (table.cell(r, ycol).empty())
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, f.response}, "empty cell");
    d.y.push_back(
        static_cast<int>(std::find(levels.begin(), levels.end(), table.cell(r, ycol)) - levels.begin()));
  }
  d.levels = static_cast<int>(levels.size());
  if (d.levels < 3)
    throw InputError(table.source + ": the response '" + f.response + "' has " + std::to_string(d.levels) +
                     " levels; an ordinal model needs at least 3 (use a logistic model for 2)");
  std::vector<std::string> vars;
  for (const auto& t : f.fixed) vars.insert(vars.end(), t.begin(), t.end());
  const auto variables = read_model_variables(table, vars, categorical);
  const ModelMatrix mm = model_matrix(f.fixed, true, variables, table.rows.size());
  d.x = mm.x.rightCols(mm.x.cols() - 1);  // the intercept is absorbed by the thresholds
  names.assign(mm.names.begin() + 1, mm.names.end());
  if (d.x.cols() > 0 && Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(mm.x).rank() < mm.x.cols())
    throw InputError(table.source +
                     ": the fixed-effects model matrix is rank deficient (a level combination is "
                     "missing or two predictors are collinear)");
  for (const auto& random : f.random) {
    InterceptTerm term;
    term.group = random.group;
    term.offset = d.q;
    term.code = grouping_codes(table, random.group, term.levels);
    term.rows_of.resize(term.levels.size());
    for (size_t r = 0; r < term.code.size(); ++r) term.rows_of[term.code[r]].push_back(r);
    if (term.rows_of.size() < 2)
      throw InputError(table.source + ": grouping factor '" + random.group + "' has a single level");
    d.q += term.rows_of.size();
    d.terms.push_back(std::move(term));
  }
  return d;
}

// Negative Hessian of the one-term Laplace log-likelihood: central differences of its analytic gradient
// (2n gradients instead of 2n^2 log-likelihoods; the steps of `information`), symmetrised.
Eigen::MatrixXd information_from_gradient(const Data& d, const std::vector<double>& at) {
  const auto n = static_cast<Eigen::Index>(at.size());
  Eigen::MatrixXd h(n, n);
  Eigen::VectorXd up, down;
  for (Eigen::Index j = 0; j < n; ++j) {
    const auto sj = static_cast<size_t>(j);
    const double step = 1e-4 * std::max(1.0, std::abs(at[sj]));
    auto v = at;
    v[sj] = at[sj] + step;
    laplace_gradient_nested(d, unpack_natural(d, v.data()), up);
    v[sj] = at[sj] - step;
    laplace_gradient_nested(d, unpack_natural(d, v.data()), down);
    h.col(j) = -(up - down) / (2.0 * step);
  }
  return 0.5 * (h + h.transpose());
}

// Negative Hessian of the Laplace log-likelihood in the natural parameters, by central differences
// (of the analytic gradient with one random term, of the log-likelihood with several).
Eigen::MatrixXd information(const Data& d, const std::vector<double>& at) {
  if (d.terms.size() == 1) return information_from_gradient(d, at);
  const auto n = static_cast<Eigen::Index>(at.size());
  auto ll = [&](const std::vector<double>& v) { return laplace_loglik(d, unpack_natural(d, v.data())); };
  Eigen::MatrixXd h(n, n);
  const double f0 = ll(at);
  std::vector<double> step(at.size());
  for (size_t i = 0; i < at.size(); ++i) step[i] = 1e-4 * std::max(1.0, std::abs(at[i]));
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i; j < n; ++j) {
      auto v = at;
      const auto si = static_cast<size_t>(i), sj = static_cast<size_t>(j);
      double value = 0;
      if (i == j) {
        v[si] = at[si] + step[si];
        const double fp = ll(v);
        v[si] = at[si] - step[si];
        value = (fp - 2.0 * f0 + ll(v)) / (step[si] * step[si]);
      } else {
        double s = 0;
        for (int a : {1, -1})
          for (int b : {1, -1}) {
            v = at;
            v[si] += a * step[si];
            v[sj] += b * step[sj];
            s += a * b * ll(v);
          }
        value = s / (4.0 * step[si] * step[sj]);
      }
      h(i, j) = h(j, i) = -value;
    }
  return h;
}
// Gradient of the Laplace log-likelihood in the natural parameters: analytic with one random term, else
// by central differences (the steps of `information`).
Eigen::VectorXd gradient(const Data& d, const std::vector<double>& at) {
  Eigen::VectorXd g(static_cast<Eigen::Index>(at.size()));
  if (d.terms.size() == 1) {
    laplace_gradient_nested(d, unpack_natural(d, at.data()), g);
    return g;
  }
  for (size_t i = 0; i < at.size(); ++i) {
    const double h = 1e-4 * std::max(1.0, std::abs(at[i]));
    auto v = at;
    v[i] = at[i] + h;
    const double up = laplace_loglik(d, unpack_natural(d, v.data()));
    v[i] = at[i] - h;
    g[static_cast<Eigen::Index>(i)] = (up - laplace_loglik(d, unpack_natural(d, v.data()))) / (2.0 * h);
  }
  return g;
}

bool thresholds_ordered(const Data& d, const std::vector<double>& natural) {
  for (int k = 1; k < d.levels - 1; ++k)
    if (!(natural[static_cast<size_t>(k)] > natural[static_cast<size_t>(k - 1)])) return false;
  return true;
}

// Newton steps x += info^-1 gradient from `natural` (updated, with `info` at it), each kept only when it
// is small (every coordinate below 0.5), keeps the thresholds ordered and does not lower the
// log-likelihood. True once a step is below 1e-9 (converged); false when a step is refused or five
// steps did not get there (e.g. a random SD running to 0, where the likelihood is flat in log sd).
bool newton_polish(const Data& d, std::vector<double>& natural, Eigen::MatrixXd& info) {
  double ll = laplace_loglik(d, unpack_natural(d, natural.data()));
  for (int it = 0; it < 5; ++it) {
    const Eigen::VectorXd step = info.ldlt().solve(gradient(d, natural));
    const double largest = step.cwiseAbs().maxCoeff();
    if (!std::isfinite(largest) || largest > 0.5) return false;
    auto next = natural;
    for (size_t i = 0; i < next.size(); ++i) next[i] += step[static_cast<Eigen::Index>(i)];
    if (!thresholds_ordered(d, next)) return false;
    const double ll_next = laplace_loglik(d, unpack_natural(d, next.data()));
    if (!(ll_next >= ll)) return false;
    natural = next;
    ll = ll_next;
    info = information(d, natural);
    if (largest < 1e-9) return true;
  }
  return false;
}

// The optimiser's coordinates of natural parameters (inverse of to_natural).
std::vector<double> from_natural(const Data& d, const std::vector<double>& natural) {
  std::vector<double> v = natural;
  for (int k = 1; k < d.levels - 1; ++k)
    v[static_cast<size_t>(k)] =
        std::log(natural[static_cast<size_t>(k)] - natural[static_cast<size_t>(k - 1)]);
  return v;
}
// The covariance of the thresholds and fixed effects: the inverse of the information matrix in
// (theta, beta, log sd). Where that matrix is singular because a random SD sits at its boundary (sd -> 0,
// so the log-likelihood is flat in log sd), the SEs are those with that SD held at its estimate: the
// inverse of the information over the other parameters (clmm then warns that the Hessian is singular
// and prints no SEs; a report needs them, and the SD's warning stays). Any other singular or
// non-positive-definite information (a separated or empty factor cell, an unidentified threshold) means
// the model is not fitted (issue 32).
Eigen::MatrixXd coefficient_covariance(const Eigen::MatrixXd& info, size_t coefficients,
                                       const std::vector<double>& natural) {
  auto well_conditioned = [](const Eigen::MatrixXd& m) {
    if (!m.allFinite()) return false;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(m, Eigen::EigenvaluesOnly);
    const double lo = eig.eigenvalues().minCoeff(), hi = eig.eigenvalues().maxCoeff();
    return eig.info() == Eigen::Success && hi > 0 && lo > 1e-10 * hi;
  };
  if (well_conditioned(info)) return info.inverse();
  std::vector<Eigen::Index> keep;
  for (size_t i = 0; i < static_cast<size_t>(info.rows()); ++i)
    if (i < coefficients || std::exp(natural[i]) >= 1e-4) keep.push_back(static_cast<Eigen::Index>(i));
  const Eigen::MatrixXd sub = info(keep, keep);
  if (keep.size() == static_cast<size_t>(info.rows()) || !well_conditioned(sub)) {
    if (!info.allFinite())
      throw ModelNotFitted("the log-likelihood's curvature at the optimum is not finite");
    throw ModelNotFitted(
        "the information matrix is singular at the optimum: an effect is not identified (a factor cell "
        "whose answers all lie at one end of the scale, i.e. separated data, or a cell without answers)");
  }
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(info.rows(), info.cols());
  const Eigen::MatrixXd sub_cov = sub.inverse();
  cov(keep, keep) = sub_cov;
  return cov;
}
}  // namespace

ClmmResult fit_clmm(const CsvTable& table, const std::string& formula, const std::string& link,
                    const std::set<std::string>& categorical) {
  if (link != "logit" && link != "probit")
    throw InputError("--link must be logit or probit, got '" + link + "'");
  require_columns(table, formula_variable_names(formula), "the formula");
  const LmmFormula f = parse_lmm_formula(formula);
  std::vector<std::string> names, levels;
  const Data d = build_data(table, f, link, categorical, names, levels);
  const size_t k1 = static_cast<size_t>(d.levels - 1), p = static_cast<size_t>(d.x.cols());
  // Start: thresholds at the link quantiles of the cumulative proportions, beta = 0, sd = 1.
  const size_t nt = d.terms.size();
  std::vector<double> v(k1 + p + nt, 0.0);
  std::vector<double> counts(static_cast<size_t>(d.levels), 0.0);
  for (int y : d.y) counts[static_cast<size_t>(y)] += 1;
  double cum = 0, prev = 0;
  const boost::math::normal_distribution<double> normal;
  for (size_t k = 0; k < k1; ++k) {
    cum += counts[k] / static_cast<double>(d.y.size());
    const double c = std::clamp(cum, 1e-3, 1 - 1e-3);
    const double q = d.link.logit ? std::log(c / (1 - c)) : boost::math::quantile(normal, c);
    v[k] = k == 0 ? q : std::log(std::max(q - prev, 1e-3));
    prev = k == 0 ? q : prev + std::exp(v[k]);
  }
  // With one random term (every study report's model): L-BFGS on the analytic gradient to a relative
  // change of 1e-15. With several, or where L-BFGS fails: BOBYQA to 1e-10. Then Newton steps on the
  // gradient and the finite-difference Hessian (which the SEs need anyway): they land closer to the
  // optimum than either optimiser's last digits (docs/analysis.md). Where Newton cannot finish (a flat
  // direction: an SD running to 0, or a coefficient running to infinity in separated data), the first
  // optimiser goes on from Newton's last point, BOBYQA to 1e-15. L-BFGS walks such a direction out in
  // tens of gradients where BOBYQA took up to its 200000 evaluations (issue 31).
  auto* data = const_cast<Data*>(&d);
  const bool gradient_based = nt == 1;
  auto optimise = [&](double bobyqa_ftol_rel) {
    if (gradient_based) {
      const auto start = v;
      const NloptOutcome lbfgs = minimise_with_gradient(v, clmm_objective_with_gradient, data, 20000);
      if (lbfgs.converged()) return lbfgs;
      v = start;
    }
    return minimise_derivative_free(v, {}, clmm_objective, data, 200000, bobyqa_ftol_rel);
  };
  NloptOutcome opt = optimise(1e-10);
  std::vector<double> natural = to_natural(d, v.data());
  Eigen::MatrixXd info = information(d, natural);
  if (!newton_polish(d, natural, info)) {
    v = from_natural(d, natural);
    opt = optimise(1e-15);
    natural = to_natural(d, v.data());
    info = information(d, natural);
  }
  const double best = -laplace_loglik(d, unpack_natural(d, natural.data()));
  ClmmResult out;
  out.link = link;
  out.observations = d.y.size();
  out.converged = opt.converged();
  out.loglik = -best;
  for (size_t t = 0; t < nt; ++t) {
    out.random.push_back({d.terms[t].group, std::exp(natural[k1 + p + t]), d.terms[t].rows_of.size()});
    if (out.random.back().sd < 1e-4)
      out.warnings.push_back("the random-effect SD of '" + d.terms[t].group + "' is (near) zero");
  }
  if (!out.converged)
    throw ModelNotFitted("the optimiser did not converge (NLopt status " + std::to_string(opt.status) + ")");
  require_finite_estimate(out.loglik, "the log-likelihood");
  const Eigen::MatrixXd cov = coefficient_covariance(info, k1 + p, natural);
  const boost::math::normal_distribution<double> z01;
  for (size_t i = 0; i < k1 + p; ++i) {
    ClmmCoefficient c;
    c.estimate = natural[i];
    c.se = std::sqrt(cov(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(i)));
    const std::string what =
        i < k1 ? "threshold " + levels[i] + "|" + levels[i + 1] : "term " + names[i - k1];
    require_finite_estimate(c.estimate, "the estimate of " + what);
    if (!(c.se > 0) || !std::isfinite(c.se))
      throw ModelNotFitted("the standard error of " + what + " is not a positive finite number");
    c.z = c.estimate / c.se;
    c.p = 2.0 * boost::math::cdf(boost::math::complement(z01, std::abs(c.z)));
    if (i < k1) {
      c.name = levels[i] + "|" + levels[i + 1];
      out.thresholds.push_back(c);
    } else {
      c.name = names[i - k1];
      out.fixed.push_back(c);
    }
  }
  return out;
}

nlohmann::json clmm_to_json(const ClmmResult& r) {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json thresholds = nlohmann::json::array(), fixed = nlohmann::json::array();
  for (const auto& t : r.thresholds)
    thresholds.push_back({{"name", t.name}, {"estimate", t.estimate}, {"se", num(t.se)}});
  for (const auto& f : r.fixed)
    fixed.push_back(
        {{"term", f.name}, {"estimate", f.estimate}, {"se", num(f.se)}, {"z", num(f.z)}, {"p", num(f.p)}});
  nlohmann::json random = nlohmann::json::array();
  for (const auto& g : r.random) random.push_back({{"group", g.group}, {"sd", g.sd}});
  return {{"thresholds", thresholds},
          {"fixed", fixed},
          {"random", random},
          {"loglik", r.loglik},
          {"link", r.link},
          {"converged", r.converged},
          {"observations", r.observations},
          {"warnings", r.warnings}};
}

}  // namespace crowdlab::analysis
