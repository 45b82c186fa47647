#include "analysis/psychometric_lapse.hpp"

#include <nlopt.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace crowdlab::analysis {
namespace {
double logistic(double t) {
  return t >= 0 ? 1.0 / (1.0 + std::exp(-t)) : std::exp(t) / (1.0 + std::exp(t));
}

// The answers on the standardised stimulus axis z = (x - centre) / scale.
struct LapseProblem {
  std::vector<double> z, y;
  int evaluations = 0;
};

// Negative log-likelihood of (a, b, lambda) with p = lambda + (1 - 2 lambda) F(a + b z), and its
// gradient (NLopt's objective signature).
double lapse_objective(unsigned n, const double* theta, double* grad, void* data) {
  auto& prob = *static_cast<LapseProblem*>(data);
  ++prob.evaluations;
  const double a = theta[0], b = theta[1], lambda = theta[2];
  double nll = 0;
  std::array<double, 3> g = {0, 0, 0};
  for (size_t i = 0; i < prob.z.size(); ++i) {
    const double f = logistic(a + b * prob.z[i]);
    const double p = std::clamp(lambda + (1.0 - 2.0 * lambda) * f, 1e-300, 1.0 - 1e-16);
    const bool yes = prob.y[i] > 0;
    nll -= yes ? std::log(p) : std::log1p(-p);
    // d(-log L)/dp = -(y/p - (1-y)/(1-p)).
    const double dl_dp = yes ? -1.0 / p : 1.0 / (1.0 - p);
    const double dp_du = (1.0 - 2.0 * lambda) * f * (1.0 - f);
    g[0] += dl_dp * dp_du;
    g[1] += dl_dp * dp_du * prob.z[i];
    g[2] += dl_dp * (1.0 - 2.0 * f);
  }
  if (grad)
    for (unsigned k = 0; k < n; ++k) grad[k] = g[k];
  return nll;
}

struct Optimum {
  std::array<double, 3> theta{};
  double nll = INFINITY;
  nlopt_result status = NLOPT_FAILURE;
};

Optimum minimise(LapseProblem& prob, const std::array<double, 3>& start) {
  nlopt_opt opt = nlopt_create(NLOPT_LD_SLSQP, 3);
  const double lower[3] = {-HUGE_VAL, -kMaxStandardSlope, 0.0};
  const double upper[3] = {HUGE_VAL, kMaxStandardSlope, kMaxLapse};
  nlopt_set_lower_bounds(opt, lower);
  nlopt_set_upper_bounds(opt, upper);
  nlopt_set_min_objective(opt, lapse_objective, &prob);
  // Tight tolerances: the estimates are compared with R's nlminb to 1e-6 (tests/analysis/).
  nlopt_set_ftol_rel(opt, 1e-15);
  nlopt_set_xtol_rel(opt, 1e-12);
  nlopt_set_maxeval(opt, 5000);
  Optimum o;
  o.theta = start;
  o.status = nlopt_optimize(opt, o.theta.data(), &o.nll);
  nlopt_destroy(opt);
  return o;
}
// Binomial negative log-likelihood of k "yes" of n at probability p (0 ln 0 = 0).
double binomial_nll(double k, double n, double p) {
  return -((k > 0 ? k * std::log(p) : 0.0) + (n - k > 0 ? (n - k) * std::log1p(-p) : 0.0));
}

struct Level {
  double x = 0, n = 0, yes = 0;
};

// The model's limit as the slope grows without bound: the step between levels `split` and `split + 1`,
// or (at_level) at level `split`, which keeps its own rate within [lambda, 1 - lambda]. `falling`: "yes"
// below the step. Lambda is the ML rate of the contrary answers off the step.
double step_limit_nll(const std::vector<Level>& levels, size_t split, bool at_level, bool falling) {
  double errors = 0, off = 0;
  for (size_t i = 0; i < levels.size(); ++i) {
    if (at_level && i == split) continue;
    const bool below = i <= split;
    errors += (below == falling) ? levels[i].n - levels[i].yes : levels[i].yes;
    off += levels[i].n;
  }
  const double lambda = std::min(errors / off, kMaxLapse);
  double nll = binomial_nll(errors, off, lambda);
  if (at_level) {
    const Level& m = levels[split];
    nll += binomial_nll(m.yes, m.n, std::clamp(m.yes / m.n, lambda, 1.0 - lambda));
  }
  return nll;
}
}  // namespace

StepSplit best_step(const std::vector<double>& x, const std::vector<double>& y) {
  std::map<double, Level> by_x;
  for (size_t i = 0; i < x.size(); ++i) {
    Level& l = by_x[x[i]];
    l.x = x[i];
    l.n += 1;
    l.yes += y[i];
  }
  std::vector<Level> levels;
  for (const auto& entry : by_x) levels.push_back(entry.second);
  const size_t last = levels.size() - 1;
  StepSplit best;
  for (size_t k = 0; k < levels.size(); ++k)
    for (bool at_level : {false, true}) {
      if (!at_level && k == last) continue;
      // The interval the threshold is confined to: between the neighbours of a step at a level.
      const double below = at_level && k > 0 ? levels[k - 1].x : levels[k].x;
      const double above = at_level ? levels[std::min(k + 1, last)].x : levels[k + 1].x;
      for (bool falling : {true, false}) {
        const double nll = step_limit_nll(levels, k, at_level, falling);
        if (nll < best.nll) best = {below, above, nll};
      }
    }
  return best;
}

double psychometric_nll(const std::vector<double>& x, const std::vector<double>& y,
                        const PsychometricFit& fit) {
  double nll = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    const double p = std::clamp(fit.probability(x[i]), 1e-300, 1.0 - 1e-16);
    nll -= y[i] > 0 ? std::log(p) : std::log1p(-p);
  }
  return nll;
}

PsychometricFit fit_symmetric_lapse(const std::vector<double>& x, const std::vector<double>& y,
                                    const PsychometricFit& plain) {
  double centre = 0, scale = 0;
  for (double v : x) centre += v;
  centre /= static_cast<double>(x.size());
  for (double v : x) scale += (v - centre) * (v - centre);
  scale = std::sqrt(scale / static_cast<double>(x.size()));  // > 0: validated >= 2 distinct x
  LapseProblem prob;
  for (double v : x) prob.z.push_back((v - centre) / scale);
  prob.y = y;
  // The plain fit on the z axis: a + b z = intercept + slope x.
  const double b0 = std::clamp(plain.slope * scale, -0.9 * kMaxStandardSlope, 0.9 * kMaxStandardSlope);
  const double a0 = plain.intercept + plain.slope * centre;
  Optimum best;
  for (double lambda0 : {0.01, 0.1}) {
    const Optimum o = minimise(prob, {a0, b0, lambda0});
    // SLSQP may stop with ROUNDOFF_LIMITED at an optimum it cannot refine further: still its best point.
    const bool usable = o.status > 0 || o.status == NLOPT_ROUNDOFF_LIMITED;
    if (usable && std::isfinite(o.nll) && o.nll < best.nll) best = o;
  }
  PsychometricFit fit;
  fit.lapse_fitted = true;
  fit.iterations = prob.evaluations;
  if (!std::isfinite(best.nll)) {
    fit = plain;
    fit.lapse_fitted = true;
    fit.converged = false;
    fit.warning = "the lapse-rate fit failed (NLopt); reporting the plain logistic fit";
    return fit;
  }
  fit.converged = best.status != NLOPT_MAXEVAL_REACHED;
  if (!fit.converged) fit.warning = "the lapse-rate fit stopped at its evaluation limit";
  const double lambda = best.theta[2] <= 1e-10 ? 0.0 : best.theta[2];
  fit.guess = fit.lapse = lambda;
  fit.lapse_at_boundary = lambda == 0.0;
  fit.slope = best.theta[1] / scale;
  fit.intercept = best.theta[0] - fit.slope * centre;
  if (std::abs(best.theta[1]) >= kMaxStandardSlope * (1.0 - 1e-9))
    fit.warning +=
        "the slope reached its bound: the answers step at the threshold, with lapses on both sides";
  // A step with lapses on either side can fit as well as any finite slope: the ML slope is then
  // infinite (the likelihood rises towards the step's as the slope grows) and the optimiser stops
  // anywhere on that ridge.
  const StepSplit step = best_step(x, y);
  if (step.nll <= best.nll + 1e-6) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%g and %g", step.below, step.above);
    fit.warning += std::string(fit.warning.empty() ? "" : "; ") +
                   "apart from lapses the answers step between x = " + buf +
                   ": the slope is not identified (the maximum-likelihood slope is infinite), and the "
                   "threshold is only known to lie in that interval";
    fit.step_not_identified = true;
  }
  if (fit.lapse_at_boundary) {
    // On the boundary the model is the plain logistic one, whose Newton fit is the exact optimum.
    fit.intercept = plain.intercept;
    fit.slope = plain.slope;
  }
  return fit;
}

}  // namespace crowdlab::analysis
