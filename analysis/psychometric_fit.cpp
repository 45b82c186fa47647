#include "analysis/psychometric_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "analysis/psychometric_lapse.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab::analysis {
namespace {
double logistic(double t) {
  return t >= 0 ? 1.0 / (1.0 + std::exp(-t)) : std::exp(t) / (1.0 + std::exp(t));
}

void validate(const std::vector<double>& x, const std::vector<double>& y, const PsychometricOptions& o) {
  if (x.size() != y.size()) throw InputError("psychometric fit: x and response have different lengths");
  std::set<double> distinct;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]))
      throw InputError("psychometric fit: non-finite x at trial " + std::to_string(i + 1));
    if (y[i] != 0.0 && y[i] != 1.0)
      throw InputError("psychometric fit: response must be 0 or 1 at trial " + std::to_string(i + 1));
    distinct.insert(x[i]);
  }
  if (distinct.size() < 2) throw InputError("psychometric fit: need at least 2 distinct x values");
  if (!(o.guess >= 0 && o.lapse >= 0 && o.guess + o.lapse < 1))
    throw InputError("psychometric fit: need guess >= 0, lapse >= 0 and guess + lapse < 1");
  if (o.fit_symmetric_lapse && (o.guess != 0 || o.lapse != 0))
    throw InputError("psychometric fit: a fitted symmetric lapse rate excludes fixed guess/lapse rates");
}

struct ModelEval {
  double loglik = 0;
  Eigen::Vector2d score = Eigen::Vector2d::Zero();
  Eigen::Matrix2d info = Eigen::Matrix2d::Zero();
};

// Log-likelihood, score and Fisher information of the guess/lapse model at beta.
ModelEval evaluate(const std::vector<double>& x, const std::vector<double>& y, const Eigen::Vector2d& beta,
                   double guess, double lapse) {
  ModelEval e;
  const double range = 1.0 - guess - lapse;
  for (size_t i = 0; i < x.size(); ++i) {
    const double f = logistic(beta[0] + beta[1] * x[i]);
    const double p = std::clamp(guess + range * f, 1e-300, 1.0 - 1e-16);
    const double dp = range * f * (1.0 - f);
    e.loglik += y[i] > 0 ? std::log(p) : std::log1p(-p);
    const Eigen::Vector2d xi(1.0, x[i]);
    const double v = p * (1.0 - p);
    e.score += (y[i] - p) / v * dp * xi;
    e.info += dp * dp / v * xi * xi.transpose();
  }
  return e;
}

PsychometricFit fit_ml(const std::vector<double>& x, const std::vector<double>& y,
                       const PsychometricOptions& o) {
  PsychometricFit fit;
  fit.guess = o.guess;
  fit.lapse = o.lapse;
  Eigen::Vector2d beta = Eigen::Vector2d::Zero();
  ModelEval cur = evaluate(x, y, beta, o.guess, o.lapse);
  for (int it = 1; it <= o.max_iterations; ++it) {
    fit.iterations = it;
    const Eigen::Vector2d step = cur.info.ldlt().solve(cur.score);
    if (!step.allFinite()) break;
    double scale = 1.0;
    Eigen::Vector2d next = beta + step;
    ModelEval ev = evaluate(x, y, next, o.guess, o.lapse);
    while (ev.loglik < cur.loglik - 1e-12 * std::abs(cur.loglik) && scale > 1e-10) {
      scale *= 0.5;
      next = beta + scale * step;
      ev = evaluate(x, y, next, o.guess, o.lapse);
    }
    beta = next;
    cur = ev;
    if ((scale * step).norm() <= 1e-13 * (1.0 + beta.norm())) {
      fit.converged = true;
      break;
    }
  }
  fit.intercept = beta[0];
  fit.slope = beta[1];
  if (!fit.converged) fit.warning = "maximum-likelihood fit did not converge";
  return fit;
}
}  // namespace

double PsychometricFit::probability(double x) const {
  return guess + (1.0 - guess - lapse) * logistic(intercept + slope * x);
}

double PsychometricFit::threshold(double p) const {
  if (!(p > 0 && p < 1) || slope == 0) return std::numeric_limits<double>::quiet_NaN();
  return (std::log(p / (1.0 - p)) - intercept) / slope;
}

bool is_separated(const std::vector<double>& x, const std::vector<double>& y) {
  double min0 = INFINITY, max0 = -INFINITY, min1 = INFINITY, max1 = -INFINITY;
  for (size_t i = 0; i < x.size(); ++i) {
    if (y[i] > 0) {
      min1 = std::min(min1, x[i]);
      max1 = std::max(max1, x[i]);
    } else {
      min0 = std::min(min0, x[i]);
      max0 = std::max(max0, x[i]);
    }
  }
  if (!std::isfinite(min0) || !std::isfinite(min1)) return true;  // one answer only
  return max0 <= min1 || max1 <= min0;
}

PsychometricFit fit_logistic_firth(const std::vector<double>& x, const std::vector<double>& y,
                                   int max_iterations) {
  PsychometricFit fit;
  Eigen::Vector2d beta = Eigen::Vector2d::Zero();
  const auto n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd design(n, 2);
  for (Eigen::Index i = 0; i < n; ++i) design.row(i) << 1.0, x[static_cast<size_t>(i)];
  for (int it = 1; it <= max_iterations; ++it) {
    fit.iterations = it;
    Eigen::VectorXd p(n), w(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      p[i] = logistic(design.row(i).dot(beta));
      w[i] = p[i] * (1.0 - p[i]);
    }
    const Eigen::Matrix2d info = design.transpose() * w.asDiagonal() * design;
    const Eigen::Matrix2d inv = info.inverse();
    // Modified score (Firth 1993): X^T (y - p + h (1/2 - p)), h the hat-matrix diagonal.
    Eigen::Vector2d score = Eigen::Vector2d::Zero();
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::Vector2d xi = design.row(i).transpose();
      const double h = w[i] * xi.dot(inv * xi);
      score += (y[static_cast<size_t>(i)] - p[i] + h * (0.5 - p[i])) * xi;
    }
    Eigen::Vector2d step = inv * score;
    // Bounded steps keep the early iterations stable (as logistf's maxstep).
    const double max_step = 5.0;
    if (step.cwiseAbs().maxCoeff() > max_step) step *= max_step / step.cwiseAbs().maxCoeff();
    beta += step;
    if (step.norm() <= 1e-12 * (1.0 + beta.norm())) {
      fit.converged = true;
      break;
    }
  }
  fit.intercept = beta[0];
  fit.slope = beta[1];
  fit.separated = is_separated(x, y);
  return fit;
}

namespace {
PsychometricFit fit_model(const std::vector<double>& x, const std::vector<double>& y,
                          const PsychometricOptions& options) {
  if (is_separated(x, y)) {
    PsychometricFit fit = fit_logistic_firth(x, y, options.max_iterations);
    fit.separated = true;
    fit.warning =
        "complete separation of the answers by x: the maximum-likelihood slope is infinite; reporting "
        "Firth's penalised-likelihood estimate (bounded)";
    if (options.guess > 0 || options.lapse > 0) fit.warning += " of the plain logistic model";
    fit.lapse_fitted = options.fit_symmetric_lapse;
    fit.lapse_at_boundary = options.fit_symmetric_lapse;
    return fit;
  }
  if (!options.fit_symmetric_lapse) return fit_ml(x, y, options);
  const PsychometricFit plain = fit_ml(x, y, options);
  return fit_symmetric_lapse(x, y, plain);
}
}  // namespace

PsychometricFit fit_psychometric(const std::vector<double>& x, const std::vector<double>& y,
                                 const PsychometricOptions& options) {
  validate(x, y, options);
  PsychometricFit fit = fit_model(x, y, options);
  fit.nll = psychometric_nll(x, y, fit);
  return fit;
}

std::vector<ThresholdInterval> bootstrap_thresholds(const std::vector<double>& x, const PsychometricFit& fit,
                                                    const std::vector<double>& probabilities, int replicates,
                                                    std::uint64_t seed, const PsychometricOptions& options,
                                                    double level) {
  if (replicates < 2) throw InputError("bootstrap: need at least 2 replicates");
  std::vector<std::vector<double>> samples(probabilities.size());
  std::vector<double> y(x.size());
  for (int b = 0; b < replicates; ++b) {
    Rng rng(derive_seed(seed, "bootstrap/" + std::to_string(b)));
    for (size_t i = 0; i < x.size(); ++i) y[i] = uniform01(rng) < fit.probability(x[i]) ? 1.0 : 0.0;
    const PsychometricFit refit = fit_psychometric(x, y, options);
    for (size_t k = 0; k < probabilities.size(); ++k) {
      const double t = refit.threshold(probabilities[k]);
      if (std::isfinite(t)) samples[k].push_back(t);
    }
  }
  std::vector<ThresholdInterval> out;
  const double alpha = 0.5 * (1.0 - level);
  for (size_t k = 0; k < probabilities.size(); ++k) {
    auto& s = samples[k];
    std::sort(s.begin(), s.end());
    ThresholdInterval ci;
    ci.p = probabilities[k];
    ci.replicates_used = static_cast<int>(s.size());
    // Type-7 sample quantiles (R's default).
    auto quantile = [&](double q) {
      if (s.empty()) return std::numeric_limits<double>::quiet_NaN();
      const double h = (static_cast<double>(s.size()) - 1.0) * q;
      const auto lo = static_cast<size_t>(std::floor(h));
      const size_t hi = std::min(lo + 1, s.size() - 1);
      return s[lo] + (h - static_cast<double>(lo)) * (s[hi] - s[lo]);
    };
    ci.lower = quantile(alpha);
    ci.upper = quantile(1.0 - alpha);
    out.push_back(ci);
  }
  return out;
}

}  // namespace crowdlab::analysis
